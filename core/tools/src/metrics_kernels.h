/* The filter kernels of SSIM and FLIP (metrics.c), shared with the device
 * scorer (device_score.c) so that both filter with the same weights. */
#ifndef VRG_METRICS_KERNELS_H
#define VRG_METRICS_KERNELS_H
#include "voxrg/metrics.h"

/* SSIM's normalised 11-tap Gaussian (sigma 1.5). */
void _vrg_ssim_kernel(double k[VRG_SSIM_WINDOW]);

/* FLIP's contrast sensitivity filters: the radius of every channel's
 * kernel, and term `term` (0 or 1) of channel `channel` (0 A, 1 RG, 2 BY):
 * its 1D kernel k[2r + 1], normalised to sum 1 (the 2D term is k(x) k(y)),
 * and its share of the channel's filter as the return value (0: the
 * channel has no such term, k untouched). */
int _vrg_flip_csf_radius(double ppd);
double _vrg_flip_csf_kernel(int channel, int term, double ppd, int r, double *k);

/* FLIP's feature detection: the radius, and the derivative kernel d (first
 * derivative, or the second with `second`) and the Gaussian g, 2r + 1 taps
 * each; the edge response along x is d along x then g along y. */
int _vrg_flip_feature_radius(double ppd);
void _vrg_flip_feature_kernels(double ppd, int second, int r, double *d, double *g);

#endif

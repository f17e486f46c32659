/* Sun and sky from the time of day: an analytic, tonemap-friendly model
 * (not a scattering simulation). Every constant is here so a GLSL copy of
 * vrg_sky_radiance can match it; units are in voxrg/camera.h. */
#include <math.h>
#include "voxrg/sky.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

/* Sun radiance at the zenith, outside any extra air. */
static const double SUN_ZENITH = 3.0;
/* Per-channel extinction per extra air mass: blue scatters most, so a low
 * sun turns orange and then red while dimming (roughly Rayleigh-shaped). */
static const double EXTINCTION[3] = {0.06, 0.14, 0.32};
/* Gradient colours by day and by night (night: dim blue, never black). */
static const double DAY_ZENITH[3] = {0.16, 0.33, 0.75};
static const double DAY_HORIZON[3] = {0.55, 0.66, 0.82};
static const double NIGHT_ZENITH[3] = {0.03, 0.045, 0.1};
static const double NIGHT_HORIZON[3] = {0.045, 0.06, 0.11};
/* Moonlight at the zenith: about a tenth of the sun, bluish (a night that
 * stays readable at the graphs' day exposure, not a physical ratio). */
static const double MOON_ZENITH[3] = {0.22, 0.27, 0.38};
/* Horizon multiplier at sunrise/sunset: warm it, take out blue. */
static const double TWILIGHT_TINT[3] = {1.6, 0.9, 0.6};

void vrg_sky_default(vrg_sky_desc *d)
{
    d->time_of_day = 10.0f;
    d->day_length = 0.0f;
    d->latitude_tilt = 30.0f;
    d->sun_azimuth = 30.0f;
}

static double clampd(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }
static double mixd(double a, double b, double t) { return a + (b - a) * t; }

/* GLSL smoothstep */
static double smoothstepd(double e0, double e1, double x)
{
    double t = clampd((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

void vrg_sky_eval(const vrg_sky_desc *d, double time_s, vrg_sky *out)
{
    double h = d->time_of_day;
    if (d->day_length > 0.0f)
        h += 24.0 * time_s / d->day_length;
    h = isfinite(h) ? fmod(h, 24.0) : 12.0;
    if (h < 0.0)
        h += 24.0;
    if ((float)h >= 24.0f) /* rounding just below 24 must not print as 24 */
        h = 0.0;
    out->hours = (float)h;

    /* The sun moves on a great circle at 15 degrees an hour: phi = 0 at
     * 6:00 (on the horizon, in the sunrise direction e), 90 at 12:00, 180 at
     * 18:00 (opposite e), 270 at 0:00. The circle's top is tilted by
     * latitude_tilt from +y towards s (horizontal, perpendicular to e), so
     * the noon elevation is 90 - |tilt| and sunrise/sunset stay at 6/18. */
    double phi = (h - 6.0) / 24.0 * 2.0 * PI;
    double az = d->sun_azimuth * DEG;
    double tilt = clampd(d->latitude_tilt == d->latitude_tilt ? d->latitude_tilt : 30.0, -89.0, 89.0) * DEG;
    double e[3] = {cos(az), 0.0, -sin(az)};  /* +x rotated by az around +y */
    double s[3] = {sin(az), 0.0, cos(az)};   /* +z rotated likewise */
    double top[3] = {s[0] * sin(tilt), cos(tilt), s[2] * sin(tilt)};
    double len2 = 0.0, dir[3];
    for (int i = 0; i < 3; i++) {
        dir[i] = cos(phi) * e[i] + sin(phi) * top[i];
        len2 += dir[i] * dir[i];
    }
    for (int i = 0; i < 3; i++)
        out->sun_dir[i] = (float)(dir[i] / sqrt(len2));
    double sin_elev = clampd(dir[1] / sqrt(len2), -1.0, 1.0);
    double elev = asin(sin_elev) / DEG;
    out->sun_elevation = (float)elev;

    /* Sun: air mass ~ 1 / sin(elevation) (flat atmosphere, capped at 20
     * near the horizon); transmission exp(-k * (airmass - 1)) so the zenith
     * sun is SUN_ZENITH white; faded to 0 over the last 3 degrees above the
     * horizon so nothing lights the world from below. */
    double airmass = 1.0 / fmax(sin_elev, 0.05);
    double fade = smoothstepd(0.0, 3.0, elev);
    for (int c = 0; c < 3; c++)
        out->sun_radiance[c] = (float)(SUN_ZENITH * exp(-EXTINCTION[c] * (airmass - 1.0)) * fade);

    /* Moon: opposite the sun, faded in over its first 3 degrees. */
    double moon_fade = smoothstepd(0.0, 3.0, -elev);
    for (int c = 0; c < 3; c++) {
        out->moon_dir[c] = -out->sun_dir[c];
        out->moon_radiance[c] = (float)(MOON_ZENITH[c] * moon_fade);
    }
    out->moon_elevation = (float)-elev;

    /* Sky: night -> day as the sun climbs from 6 degrees below the horizon
     * (end of civil twilight) to 12 above; the horizon gets the twilight
     * tint with a bell-shaped weight around elevation 0. */
    double day = smoothstepd(-6.0, 12.0, elev);
    double twilight = exp(-(elev - 1.0) * (elev - 1.0) / 50.0);
    for (int c = 0; c < 3; c++) {
        double zen = mixd(NIGHT_ZENITH[c], DAY_ZENITH[c], day);
        double hor = mixd(NIGHT_HORIZON[c], DAY_HORIZON[c], day) * mixd(1.0, TWILIGHT_TINT[c], twilight);
        out->sky_zenith[c] = (float)zen;
        out->sky_horizon[c] = (float)hor;
        /* mean of mix(hor, zen, sqrt(y)) weighted by y over the hemisphere:
         * integral of 2y * sqrt(y) dy over [0, 1] = 0.8 */
        out->ambient[c] = (float)mixd(hor, zen, 0.8);
    }
}

void vrg_sky_key_light(const vrg_sky *s, float dir[3], float *elevation, float radiance[3])
{
    int sun = s->sun_elevation > 0.0f;
    for (int c = 0; c < 3; c++) {
        dir[c] = sun ? s->sun_dir[c] : s->moon_dir[c];
        radiance[c] = sun ? s->sun_radiance[c] : s->moon_radiance[c];
    }
    *elevation = sun ? s->sun_elevation : s->moon_elevation;
}

/* The formula (GLSL copies must match):
 *   y >= 0:  base = mix(horizon, zenith, sqrt(y))
 *   y <  0:  base = horizon * (0.3 + 0.7 * exp(8 * y))   (ground haze, darker downwards)
 *   c = max(dot(dir, key_dir), 0)      (vrg_sky_key_light: the sun, the moon by night)
 *   out = base + key_radiance * (0.25 * c^32 + 0.05 * c^4)   (glow, no disc) */
void vrg_sky_radiance(const vrg_sky *s, const float dir[3], float out[3])
{
    float y = dir[1], key[3], key_radiance[3], key_elevation;
    vrg_sky_key_light(s, key, &key_elevation, key_radiance); /* the glow is around it: the moon's by night */
    float c = dir[0] * key[0] + dir[1] * key[1] + dir[2] * key[2];
    c = c > 0.0f ? c : 0.0f;
    float c2 = c * c, c4 = c2 * c2, c8 = c4 * c4, c16 = c8 * c8, c32 = c16 * c16;
    float glow = 0.25f * c32 + 0.05f * c4;
    for (int i = 0; i < 3; i++) {
        float base = y >= 0.0f ? s->sky_horizon[i] + (s->sky_zenith[i] - s->sky_horizon[i]) * sqrtf(y)
                               : s->sky_horizon[i] * (0.3f + 0.7f * expf(8.0f * y));
        out[i] = base + key_radiance[i] * glow;
    }
}

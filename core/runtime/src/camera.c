/* Camera matrices and primary rays; conventions are documented in
 * voxrg/camera.h. Internals use double so that a ray and the projection
 * agree to far below a pixel even for large worlds. */
#include <math.h>
#include <string.h>
#include "voxrg/camera.h"

#define DEG (3.14159265358979323846 / 180.0)

void vrg_camera_default(vrg_camera *c)
{
    memset(c, 0, sizeof *c);
    c->fov_y = 70.0f;
    c->near_plane = 0.05f;
    c->far_plane = 1000.0f;
}

int vrg_camera_angle_range(const char *angle, double *lo, double *hi)
{
    static const struct {
        const char *name;
        double lo, hi;
    } ranges[] = {{"yaw", -360, 360}, {"pitch", -89, 89}, {"fov", 1, 179}};
    for (size_t i = 0; i < sizeof ranges / sizeof *ranges; i++)
        if (strcmp(angle, ranges[i].name) == 0) {
            *lo = ranges[i].lo;
            *hi = ranges[i].hi;
            return 0;
        }
    return -1;
}

static double clampd(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }

int vrg_camera_position_in_world(const float p[3])
{
    for (int a = 0; a < 3; a++)
        if (!(fabsf(p[a]) <= VRG_WORLD_LIMIT)) /* NaN fails too */
            return 0;
    return 1;
}

float vrg_world_clamp(float v)
{
    if (v != v)
        return 0.0f;
    return v < -VRG_WORLD_LIMIT ? -VRG_WORLD_LIMIT : v > VRG_WORLD_LIMIT ? VRG_WORLD_LIMIT : v;
}

int vrg_world_floor(float v) { return (int)floorf(vrg_world_clamp(v)); }

/* Pitch at exactly +-90 would make forward parallel to +y and the right
 * vector undefined; NaN angles become 0 so a bad value cannot poison the
 * matrices. */
static double used_pitch(const vrg_camera *c)
{
    return c->pitch == c->pitch ? clampd(c->pitch, -89.0, 89.0) : 0.0;
}

/* The camera's orthonormal basis: right, up, forward (world space). */
static void basis(const vrg_camera *c, double r[3], double u[3], double f[3])
{
    double yaw = c->yaw == c->yaw ? c->yaw * DEG : 0.0, pitch = used_pitch(c) * DEG;
    double sy = sin(yaw), cy = cos(yaw), sp = sin(pitch), cp = cos(pitch);
    f[0] = -sy * cp;
    f[1] = sp;
    f[2] = -cy * cp;
    r[0] = cy;
    r[1] = 0.0;
    r[2] = -sy;
    /* up = right x forward */
    u[0] = r[1] * f[2] - r[2] * f[1];
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
}

/* 1 / tan(fov_y / 2): the projection's vertical scale. */
static double focal(const vrg_camera *c)
{
    double fov = c->fov_y == c->fov_y ? clampd(c->fov_y, 1.0, 179.0) : 70.0;
    return 1.0 / tan(fov * DEG * 0.5);
}

void vrg_camera_forward(const vrg_camera *c, float out[3])
{
    double r[3], u[3], f[3];
    basis(c, r, u, f);
    for (int i = 0; i < 3; i++)
        out[i] = (float)f[i];
}

void vrg_camera_view(const vrg_camera *c, float out[16])
{
    double r[3], u[3], f[3], p[3] = {c->position[0], c->position[1], c->position[2]};
    basis(c, r, u, f);
    /* Rows are right, up, -forward (view space looks down -z); the
     * translation moves the camera to the origin. */
    for (int i = 0; i < 3; i++) {
        out[i * 4 + 0] = (float)r[i];
        out[i * 4 + 1] = (float)u[i];
        out[i * 4 + 2] = (float)-f[i];
        out[i * 4 + 3] = 0.0f;
    }
    out[12] = (float)-(r[0] * p[0] + r[1] * p[1] + r[2] * p[2]);
    out[13] = (float)-(u[0] * p[0] + u[1] * p[1] + u[2] * p[2]);
    out[14] = (float)(f[0] * p[0] + f[1] * p[1] + f[2] * p[2]);
    out[15] = 1.0f;
}

void vrg_camera_projection(const vrg_camera *c, float aspect, float out[16])
{
    double g = focal(c), a = aspect > 0.0f ? aspect : 1.0;
    double n = c->near_plane > 0.0f ? c->near_plane : 0.05;
    double f = c->far_plane > n ? c->far_plane : n * 2.0;
    memset(out, 0, 16 * sizeof *out);
    out[0] = (float)(g / a);
    out[5] = (float)-g;                 /* Vulkan NDC y points down */
    out[10] = (float)(f / (n - f));     /* z_view = -n -> depth 0, -f -> 1 */
    out[11] = -1.0f;                    /* w = -z_view */
    out[14] = (float)(n * f / (n - f));
}

void vrg_camera_view_projection(const vrg_camera *c, float aspect, float out[16])
{
    float v[16], p[16];
    vrg_camera_view(c, v);
    vrg_camera_projection(c, aspect, p);
    vrg_mat4_mul(p, v, out);
}

void vrg_mat4_mul(const float a[16], const float b[16], float out[16])
{
    float t[16]; /* out may alias a or b */
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++)
                s += (double)a[k * 4 + row] * b[col * 4 + k];
            t[col * 4 + row] = (float)s;
        }
    memcpy(out, t, sizeof t);
}

/* Gauss-Jordan elimination with partial pivoting on [m | I], in double. */
int vrg_mat4_invert(const float m[16], float out[16])
{
    double a[4][8];
    double scale = 0.0;
    for (int row = 0; row < 4; row++)
        for (int col = 0; col < 4; col++) {
            a[row][col] = m[col * 4 + row];
            a[row][col + 4] = row == col;
            scale = fmax(scale, fabs(a[row][col]));
        }
    if (!(scale > 0.0) || !isfinite(scale))
        return -1;
    for (int col = 0; col < 4; col++) {
        int pivot = col;
        for (int row = col + 1; row < 4; row++)
            if (fabs(a[row][col]) > fabs(a[pivot][col]))
                pivot = row;
        /* Relative threshold: a pivot this small means m is singular up to
         * float rounding, and its "inverse" would be noise. */
        if (fabs(a[pivot][col]) <= scale * 1e-12)
            return -1;
        if (pivot != col)
            for (int k = 0; k < 8; k++) {
                double t = a[col][k];
                a[col][k] = a[pivot][k];
                a[pivot][k] = t;
            }
        double inv = 1.0 / a[col][col];
        for (int k = 0; k < 8; k++)
            a[col][k] *= inv;
        for (int row = 0; row < 4; row++) {
            if (row == col || a[row][col] == 0.0)
                continue;
            double factor = a[row][col];
            for (int k = 0; k < 8; k++)
                a[row][k] -= factor * a[col][k];
        }
    }
    for (int row = 0; row < 4; row++)
        for (int col = 0; col < 4; col++)
            out[col * 4 + row] = (float)a[row][col + 4];
    return 0;
}

void vrg_camera_ray(const vrg_camera *c, uint32_t width, uint32_t height, float px, float py, float dir[3])
{
    double w = width ? width : 1, h = height ? height : 1;
    double g = focal(c), aspect = w / h;
    /* Pixel centre -> NDC (y down, as the projection), then invert the
     * projection's scales to get the view-space point at z = -1. */
    double nx = 2.0 * (px + 0.5) / w - 1.0;
    double ny = 2.0 * (py + 0.5) / h - 1.0;
    double vx = nx * aspect / g, vy = -ny / g;
    double r[3], u[3], f[3], d[3];
    basis(c, r, u, f);
    for (int i = 0; i < 3; i++)
        d[i] = vx * r[i] + vy * u[i] + f[i];
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int i = 0; i < 3; i++)
        dir[i] = (float)(d[i] / len);
}

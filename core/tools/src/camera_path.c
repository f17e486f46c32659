/* Camera paths: parsing keyframe files and evaluating the interpolated
 * camera. The file format and the curve are documented in voxrg/camera.h. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "voxrg/camera_path.h"
#include "voxrg/plugin.h"

#define FIELDS 6
#define MAX_FILE_BYTES (16u << 20) /* far beyond any hand-written path */

static FILE *out_of(FILE *diag) { return diag ? diag : stderr; }

static void error_at(FILE *diag, const char *name, int line, const char *hint, const char *msg)
{
    FILE *o = out_of(diag);
    fprintf(o, "%s:%d: error: %s\n", name, line, msg);
    if (hint)
        fprintf(o, "  hint: %s\n", hint);
}

static int is_space(char ch) { return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\v' || ch == '\f'; }

/* A field as written, escaped for a message (it is the file's text). */
static const char *as_written(const char *s, size_t len, char *out, size_t cap) { return vrg_escape(out, cap, s, len); }

/* Reads one field [s, s+len) as a finite float. Returns 0 with the value
 * as written in *written (a double) and as kept in *value, or -1 with the
 * reason in msg. The token is copied because strtod would otherwise skip
 * newlines and read into the next line. */
static int parse_field(const char *s, size_t len, double *written, float *value, char *msg, size_t msg_size)
{
    char buf[64], shown[4 * 40 + 4];
    if (len >= sizeof buf) {
        snprintf(msg, msg_size, "'%s' is not a number", as_written(s, len, shown, sizeof shown));
        return -1;
    }
    memcpy(buf, s, len);
    buf[len] = '\0';
    char *end;
    double v = strtod(buf, &end);
    if (end != buf + len) {
        snprintf(msg, msg_size, "'%s' is not a number", as_written(s, len, shown, sizeof shown));
        return -1;
    }
    /* decimal only, as graph files (validate.c): strtod also takes hex */
    if (strpbrk(buf, "xX")) {
        snprintf(msg, msg_size, "'%s' is not a decimal number", as_written(s, len, shown, sizeof shown));
        return -1;
    }
    /* strtod accepts "nan" and "inf", and a finite double can overflow float */
    if (!isfinite(v) || !isfinite((float)v)) {
        snprintf(msg, msg_size, "'%s' is not a finite number", as_written(s, len, shown, sizeof shown));
        return -1;
    }
    *written = v;
    *value = (float)v;
    return 0;
}

/* Yaw and pitch within the ranges a graph's [camera] holds them to. */
static int angle_ok(const char *angle, double v, const char *tok, size_t len, char *msg, size_t msg_size)
{
    double lo, hi;
    char shown[4 * 64];
    vrg_camera_angle_range(angle, &lo, &hi);
    if (v >= lo && v <= hi)
        return 1;
    snprintf(msg, msg_size, "%s %s is outside [%g, %g]", angle, as_written(tok, len, shown, sizeof shown), lo, hi);
    return 0;
}

/* A keyframe line's time as written, for the order check's message. */
typedef struct written_time {
    double value;
    char text[4 * 64];
} written_time;

/* Parses the line [s, e): 1 = a keyframe in *key (its time as written in
 * *time), 0 = nothing (blank or comment), -1 = an error reported. */
static int parse_line(const char *name, int line, const char *s, const char *e, vrg_camera_key *key, written_time *time, FILE *diag)
{
    const char *tok[FIELDS];
    size_t tok_len[FIELDS];
    int n = 0;
    for (const char *c = s; c < e && *c != '#' && *c != ';';) {
        if (is_space(*c)) {
            c++;
            continue;
        }
        const char *start = c;
        while (c < e && !is_space(*c) && *c != '#' && *c != ';')
            c++;
        if (n < FIELDS) {
            tok[n] = start;
            tok_len[n] = (size_t)(c - start);
        }
        n++;
    }
    if (n == 0)
        return 0;
    char msg[1024];
    if (n != FIELDS) {
        snprintf(msg, sizeof msg, "expected %d fields (time x y z yaw pitch), found %d", FIELDS, n);
        error_at(diag, name, line, "one keyframe per line: seconds, then position in blocks, then yaw and pitch in degrees", msg);
        return -1;
    }
    float v[FIELDS];
    double d[FIELDS];
    for (int i = 0; i < FIELDS; i++)
        if (parse_field(tok[i], tok_len[i], &d[i], &v[i], msg, sizeof msg) < 0) {
            error_at(diag, name, line, "fields are decimal numbers such as 12, -3.5 or 1e2", msg);
            return -1;
        }
    if (!angle_ok("yaw", d[4], tok[4], tok_len[4], msg, sizeof msg)) {
        error_at(diag, name, line, "any direction is within one turn either way, as in a graph's [camera]", msg);
        return -1;
    }
    if (!angle_ok("pitch", d[5], tok[5], tok_len[5], msg, sizeof msg)) {
        error_at(diag, name, line, "the camera cannot look straight up or down", msg);
        return -1;
    }
    if (!(fabs(d[1]) <= VRG_WORLD_LIMIT && fabs(d[2]) <= VRG_WORLD_LIMIT && fabs(d[3]) <= VRG_WORLD_LIMIT)) {
        char hint_world[96], x[4 * 64], y[4 * 64], z[4 * 64];
        snprintf(msg, sizeof msg, "position %s %s %s is outside the world", as_written(tok[1], tok_len[1], x, sizeof x),
                 as_written(tok[2], tok_len[2], y, sizeof y), as_written(tok[3], tok_len[3], z, sizeof z));
        snprintf(hint_world, sizeof hint_world, "x, y and z lie in [%.0f, %.0f] (VRG_WORLD_LIMIT)", -VRG_WORLD_LIMIT, VRG_WORLD_LIMIT);
        error_at(diag, name, line, hint_world, msg);
        return -1;
    }
    *key = (vrg_camera_key){v[0], {v[1], v[2], v[3]}, v[4], v[5]};
    time->value = d[0];
    as_written(tok[0], tok_len[0], time->text, sizeof time->text);
    return 1;
}

/* Times are kept as floats: two written times can differ and still be one
 * float (1e-300 and 0), and the message says so rather than "0 is not
 * after 0". */
static void order_error(FILE *diag, const char *name, int line, const written_time *t, const vrg_camera_key *key, const written_time *prev,
                        int prev_line)
{
    char msg[1024];
    int n = snprintf(msg, sizeof msg, "time %s is not after %s (the keyframe on line %d)", t->text, prev->text, prev_line);
    if (t->value > prev->value && n > 0 && (size_t)n < sizeof msg)
        snprintf(msg + n, sizeof msg - (size_t)n, ": as 32-bit floats, which hold times, both are %.9g", (double)key->time);
    error_at(diag, name, line, "keyframe times must strictly increase", msg);
}

int vrg_camera_path_parse(const char *name, const char *text, vrg_camera_path *out, FILE *diag)
{
    memset(out, 0, sizeof *out);
    snprintf(out->path, sizeof out->path, "%s", name ? name : "<camera path>");
    const char *nm = out->path;
    int errors = 0, cap = 0, prev_line = 0;
    vrg_camera_key *keys = NULL;
    written_time prev_time = {0};
    int count = 0;
    const char *s = text ? text : "";
    for (int line = 1;; line++) {
        const char *e = strchr(s, '\n');
        if (!e)
            e = s + strlen(s);
        vrg_camera_key key;
        written_time time;
        int r = parse_line(nm, line, s, e, &key, &time, diag);
        if (r < 0)
            errors++;
        /* Order is checked against the last good key, so one bad line does
         * not also make the next one look out of order. */
        if (r > 0 && count > 0 && !(key.time > keys[count - 1].time)) {
            order_error(diag, nm, line, &time, &key, &prev_time, prev_line);
            errors++;
            r = 0;
        }
        if (r > 0) {
            if (count == cap) {
                cap = cap ? cap * 2 : 16;
                vrg_camera_key *grown = realloc(keys, (size_t)cap * sizeof *keys);
                if (!grown) {
                    fprintf(out_of(diag), "%s: error: out of memory\n", nm);
                    free(keys);
                    return -1;
                }
                keys = grown;
            }
            keys[count++] = key;
            prev_line = line;
            prev_time = time;
        }
        if (!*e)
            break;
        s = e + 1;
    }
    if (count == 0 && errors == 0) {
        error_at(diag, nm, 1, "add lines 'time x y z yaw pitch', e.g. '0 0 40 0 0 0'", "no keyframes");
        errors++;
    }
    if (errors) {
        free(keys);
        return -1;
    }
    out->keys = keys;
    out->count = count;
    return 0;
}

int vrg_camera_path_load(const char *file, vrg_camera_path *out, FILE *diag)
{
    memset(out, 0, sizeof *out);
    FILE *f = vrg_fopen_regular(file, "rb");
    if (!f) {
        fprintf(out_of(diag), "%s: error: cannot open camera path: %s\n", file, vrg_open_strerror(errno));
        fprintf(out_of(diag), "  hint: camera paths are text files such as graphs/paths/orbit.path\n");
        return -1;
    }
    char *text = malloc(MAX_FILE_BYTES + 1);
    size_t n = text ? fread(text, 1, MAX_FILE_BYTES + 1, f) : 0;
    int read_error = ferror(f);
    fclose(f);
    const char *why = !text ? "out of memory"
                    : read_error ? "read error"
                    : n > MAX_FILE_BYTES ? "larger than 16 MiB"
                    : memchr(text, '\0', n) ? "not a text file (it contains a NUL byte)"
                    : NULL;
    if (why) {
        fprintf(out_of(diag), "%s: error: cannot read camera path: %s\n", file, why);
        free(text);
        return -1;
    }
    text[n] = '\0';
    int r = vrg_camera_path_parse(file, text, out, diag);
    free(text);
    return r;
}

void vrg_camera_path_free(vrg_camera_path *p)
{
    if (!p)
        return;
    free(p->keys);
    p->keys = NULL;
    p->count = 0;
}

float vrg_camera_path_duration(const vrg_camera_path *p)
{
    return p && p->count > 0 ? p->keys[p->count - 1].time : 0.0f;
}

/* d moved by a multiple of 360 into (-180, 180]. */
static double wrap180(double d) { return d - 360.0 * ceil((d - 180.0) / 360.0); }

/* The interpolated channels: x, y, z, unwrapped yaw, pitch. */
#define CH 5

static void key_values(const vrg_camera_key *k, double yaw, double v[CH])
{
    v[0] = k->position[0];
    v[1] = k->position[1];
    v[2] = k->position[2];
    v[3] = yaw;
    v[4] = k->pitch;
}

/* The curve can overshoot keys at the world's edge; a double beyond float's
 * range must not reach the conversion either. */
static float world_clamp(double v)
{
    return v != v ? 0.0f : v < -VRG_WORLD_LIMIT ? -VRG_WORLD_LIMIT : v > VRG_WORLD_LIMIT ? VRG_WORLD_LIMIT : (float)v;
}

static void write_camera(const double v[CH], vrg_camera *c)
{
    for (int i = 0; i < 3; i++)
        c->position[i] = world_clamp(v[i]);
    c->yaw = (float)v[3];
    c->pitch = (float)(v[4] < -89.0 ? -89.0 : v[4] > 89.0 ? 89.0 : v[4]);
}

void vrg_camera_path_eval(const vrg_camera_path *p, float time, vrg_camera *inout)
{
    if (!p || p->count <= 0 || !p->keys)
        return;
    const vrg_camera_key *k = p->keys;
    int n = p->count;
    double t = time;
    /* Segment i: k[i].time <= t < k[i+1].time (binary search). NaN and
     * times before the first key fall to key 0. */
    int i;
    if (!(t > k[0].time))
        i = -1;
    else if (t >= k[n - 1].time)
        i = n - 1;
    else {
        int lo = 0, hi = n - 1;
        while (hi - lo > 1) {
            int mid = lo + (hi - lo) / 2;
            if (k[mid].time <= t)
                lo = mid;
            else
                hi = mid;
        }
        i = lo;
    }
    /* Unwrapped yaw of keys 0 .. min(i+2, n-1); only the last few matter. */
    int last = i + 2 < n - 1 ? i + 2 : n - 1;
    double yaw[4] = {0};
    double y = k[0].yaw;
    for (int j = 0; j <= last; j++) {
        if (j > 0)
            y += wrap180((double)k[j].yaw - k[j - 1].yaw);
        if (j >= i - 1)
            yaw[j - (i - 1)] = y;
    }
    double v[CH];
    if (i < 0 || i == n - 1) {
        /* Clamped ends; yaw stays the unwrapped value so it does not jump. */
        int at = i < 0 ? 0 : n - 1;
        key_values(&k[at], i < 0 ? k[0].yaw : yaw[at - (i - 1)], v);
        write_camera(v, inout);
        return;
    }
    /* The four keys around segment i, with the ends duplicated; their time
     * gaps, with a duplicated end mirroring the segment's own gap. */
    int i0 = i > 0 ? i - 1 : i, i3 = i + 2 < n ? i + 2 : i + 1;
    double p0[CH], p1[CH], p2[CH], p3[CH];
    key_values(&k[i0], i > 0 ? yaw[0] : yaw[1], p0);
    key_values(&k[i], yaw[1], p1);
    key_values(&k[i + 1], yaw[2], p2);
    key_values(&k[i3], i + 2 < n ? yaw[3] : yaw[2], p3);
    double d1 = (double)k[i + 1].time - k[i].time;
    double d0 = i > 0 ? (double)k[i].time - k[i - 1].time : d1;
    double d2 = i + 2 < n ? (double)k[i + 2].time - k[i + 1].time : d1;
    double u = (t - k[i].time) / d1, u2 = u * u, u3 = u2 * u;
    /* Cubic Hermite basis. */
    double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    for (int c = 0; c < CH; c++) {
        double s0 = (p1[c] - p0[c]) / d0, s1 = (p2[c] - p1[c]) / d1, s2 = (p3[c] - p2[c]) / d2;
        /* Catmull-Rom tangent with time knots: each slope weighted by the
         * other gap (equals (p2 - p0) / (2 d) when the gaps are equal). */
        double m1 = (s0 * d1 + s1 * d0) / (d0 + d1);
        double m2 = (s1 * d2 + s2 * d1) / (d1 + d2);
        v[c] = h00 * p1[c] + h10 * d1 * m1 + h01 * p2[c] + h11 * d1 * m2;
    }
    write_camera(v, inout);
}

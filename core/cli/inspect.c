/* `voxrg inspect` (inspect.h): the table of vrg_graph_read_pixels, and
 * where the graph has a motion image (the gbuffer's, in pixels: current
 * minus previous position), the pixel the motion vector points to. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "inspect.h"
#include "util.h"
#include "voxrg/output.h"

int vrg_cli_parse_pixel(const char *s, uint32_t *x, uint32_t *y)
{
    unsigned long v[2];
    const char *p = s;
    for (int i = 0; i < 2; i++) {
        char *end;
        if (*p < '0' || *p > '9')
            return -1;
        v[i] = strtoul(p, &end, 10);
        if (v[i] >= VRG_CLI_SIZE_MAX || end == p)
            return -1;
        p = end;
        if (i == 0 && *p++ != ',')
            return -1;
    }
    if (*p)
        return -1;
    *x = (uint32_t)v[0];
    *y = (uint32_t)v[1];
    return 0;
}

/* The graph's motion image: named motion or PASS.motion, two channels. */
static int is_motion(const vrg_pixel_value *v)
{
    size_t n = strlen(v->resource);
    return !v->prev && !v->is_uint && v->channels == 2 && v->kept &&
           (!strcmp(v->resource, "motion") || (n > 7 && !strcmp(v->resource + n - 7, ".motion")));
}

/* A JSON number, or a string for what JSON has no number for. */
static void json_number(FILE *f, const vrg_pixel_value *v, uint32_t c)
{
    double d = v->value[c];
    if (v->is_uint)
        fprintf(f, "%u", v->bits[c]);
    else if (isnan(d))
        fprintf(f, "\"%snan\"", signbit(d) ? "-" : "");
    else if (isinf(d))
        fprintf(f, "\"%sinf\"", d < 0 ? "-" : "");
    else
        fprintf(f, "%.17g", d);
}

static void write_json(FILE *f, const char *graph_path, uint32_t x, uint32_t y, uint32_t w, uint32_t h, uint64_t frame, const vrg_pixel_value *v,
                       int n)
{
    char s1[4096], s2[512];
    fprintf(f, "{\n  \"graph\": \"%s\",\n  \"pixel\": [%u, %u],\n  \"size\": [%u, %u],\n  \"frame\": %llu,\n  \"images\": [",
            vrg_cli_json_str(graph_path, s1, sizeof s1), x, y, w, h, (unsigned long long)frame);
    int motion = -1;
    for (int i = 0; i < n; i++) {
        fprintf(f, "%s\n    {\"pass\": \"%s\", ", i ? "," : "", vrg_cli_json_str(v[i].pass, s1, sizeof s1));
        fprintf(f, "\"resource\": \"%s\", \"prev\": %s, \"format\": \"%s\", \"texel\": [%u, %u], \"resource_size\": [%u, %u], \"kept\": %s",
                vrg_cli_json_str(v[i].resource, s2, sizeof s2), v[i].prev ? "true" : "false", vrg_format_label(v[i].format), v[i].x, v[i].y,
                v[i].width, v[i].height, v[i].kept ? "true" : "false");
        fprintf(f, ", \"values\": [");
        for (uint32_t c = 0; v[i].kept && c < v[i].channels; c++) {
            fprintf(f, "%s", c ? ", " : "");
            json_number(f, &v[i], c);
        }
        fprintf(f, "], \"bits\": [");
        for (uint32_t c = 0; v[i].kept && c < v[i].channels; c++)
            fprintf(f, "%s%u", c ? ", " : "", v[i].bits[c]);
        fprintf(f, "]}");
        if (motion < 0 && is_motion(&v[i]))
            motion = i;
    }
    fprintf(f, "\n  ]");
    if (motion >= 0 && isfinite(v[motion].value[0]) && isfinite(v[motion].value[1])) {
        const vrg_pixel_value *m = &v[motion];
        double tx = floor(m->x - m->value[0] + 0.5), ty = floor(m->y - m->value[1] + 0.5);
        int on = tx >= 0 && ty >= 0 && tx < m->width && ty < m->height;
        fprintf(f, ",\n  \"motion\": {\"resource\": \"%s\", \"vector\": [%.17g, %.17g], \"previous_pixel\": [%.0f, %.0f], \"on_screen\": %s}",
                vrg_cli_json_str(m->resource, s2, sizeof s2), m->value[0], m->value[1], tx, ty, on ? "true" : "false");
    }
    fprintf(f, "\n}\n");
}

int vrg_cli_inspect_report(vrg_graph *g, const char *graph_path, uint32_t x, uint32_t y, uint64_t frame, FILE *out, const char *json)
{
    uint32_t w, h;
    vrg_graph_size(g, &w, &h);
    /* a first guess; the call says how many there are: then room for all */
    int cap = 16;
    vrg_pixel_value *v = calloc((size_t)cap, sizeof *v);
    if (!v) {
        fprintf(stderr, "error: pixel %u,%u: out of memory\n", x, y);
        return -1;
    }
    int n = vrg_graph_read_pixels(g, x, y, v, (uint32_t)cap);
    if (n > cap) {
        free(v);
        cap = n;
        v = calloc((size_t)cap, sizeof *v);
        if (!v) {
            fprintf(stderr, "error: pixel %u,%u: out of memory for %d rows\n", x, y, n);
            return -1;
        }
        n = vrg_graph_read_pixels(g, x, y, v, (uint32_t)cap);
    }
    if (n < 0 || n > cap) { /* n > cap: the graph cannot change between the calls */
        free(v);
        return -1;
    }
    fprintf(out, "pixel %u,%u of %ux%u, frame %llu, %s\n", x, y, w, h, (unsigned long long)frame, graph_path);
    fprintf(out, "%-20s %-28s %-11s %-11s %s\n", "pass", "resource", "format", "texel", "value");
    int motion = -1;
    for (int i = 0; i < n; i++) {
        char name[160], texel[32], text[256];
        snprintf(name, sizeof name, "%s%s", v[i].resource, v[i].prev ? "@prev" : "");
        snprintf(texel, sizeof texel, "%u,%u", v[i].x, v[i].y);
        fprintf(out, "%-20s %-28s %-11s %-11s %s\n", v[i].prev ? "" : v[i].pass, name, vrg_format_label(v[i].format), texel,
                vrg_pixel_value_text(&v[i], text, sizeof text));
        if (motion < 0 && is_motion(&v[i]))
            motion = i;
    }
    if (motion >= 0) {
        const vrg_pixel_value *m = &v[motion];
        if (isfinite(m->value[0]) && isfinite(m->value[1])) {
            double tx = floor(m->x - m->value[0] + 0.5), ty = floor(m->y - m->value[1] + 0.5);
            int on = tx >= 0 && ty >= 0 && tx < m->width && ty < m->height;
            fprintf(out, "motion (%s): the previous frame's pixel %.0f,%.0f%s\n", m->resource, tx, ty, on ? "" : " (off screen: disoccluded)");
        } else
            fprintf(out, "motion (%s): not finite\n", m->resource);
    }
    int rc = 0;
    if (json) {
        vrg_output *o = vrg_output_open(json);
        if (!o)
            rc = -1;
        else {
            write_json(vrg_output_stream(o), graph_path, x, y, w, h, frame, v, n);
            rc = vrg_output_commit(o);
            if (rc == 0)
                fprintf(stderr, "wrote %s\n", json);
        }
    }
    free(v);
    return rc;
}

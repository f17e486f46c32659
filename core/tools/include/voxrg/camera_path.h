/* Keyframed camera paths (tools layer): files of keyframes, sampled per frame
 * into a vrg_camera. */
#ifndef VOXRG_CAMERA_PATH_H
#define VOXRG_CAMERA_PATH_H
#include <stdio.h>
#include "voxrg/camera.h"
#ifdef __cplusplus
extern "C" {
#endif
/* Only what these headers declare is exported from libvoxrg_tools (built with
 * -fvisibility=hidden). */
#pragma GCC visibility push(default)

/* ---- camera paths ----
 * A text file, one keyframe per line:  time x y z yaw pitch
 * (seconds, blocks, degrees), fields separated by spaces or tabs. '#' or ';'
 * starts a comment (to the end of the line); blank lines are ignored. Times
 * strictly increase (as floats); yaw and pitch are within
 * vrg_camera_angle_range's ranges, as a graph's [camera]; x, y and z are
 * within VRG_WORLD_LIMIT; at least one keyframe. Numbers are decimal, as in graph
 * files: hexadecimal, "inf" and "nan" are refused. */
typedef struct vrg_camera_key {
    float time, position[3], yaw, pitch;
} vrg_camera_key;

typedef struct vrg_camera_path {
    vrg_camera_key *keys; /* as written in the file */
    int count;
    char path[512];       /* the name used in messages */
} vrg_camera_path;

/* Both return 0, or -1 after printing "NAME:LINE: error: message" and a
 * "  hint: ..." line to diag (NULL: stderr) for every bad line: wrong field
 * count, not a number (hexadecimal included), NaN/inf, yaw or pitch out of range,
 * a position outside the world, time not increasing; and
 * "NAME:1: error: ..." when there is no keyframe at all (load: "FILE: error:
 * cannot open/read camera path: why" when the file itself fails). On -1, *out holds no
 * keys (count 0, keys NULL) and needs no free; on 0, free it with
 * vrg_camera_path_free. Numbers are read with strtod: the C locale is
 * assumed. */
int vrg_camera_path_load(const char *file, vrg_camera_path *out, FILE *diag);
int vrg_camera_path_parse(const char *name_for_messages, const char *text, vrg_camera_path *out, FILE *diag);
void vrg_camera_path_free(vrg_camera_path *p);

/* Writes position, yaw and pitch at `time` (seconds; the keys' own clock).
 * The curve is Catmull-Rom with the key times as knots (cubic Hermite whose
 * tangent at key i is the time-weighted mean of the slopes of its two
 * segments): it passes through every key at its time, its velocity is
 * continuous, and for evenly spaced keys it is exactly uniform Catmull-Rom.
 * The ends are clamped by duplicating the first and last key. Before the
 * first key: the first key; after the last: the last key.
 * Yaw is unwrapped first: each key's yaw is moved by a multiple of 360 so it
 * is within (-180, 180] of the previous key's, so 350 -> 10 turns +20, not
 * -340 (a step of exactly 180 turns +180: put a key in between to pick the
 * direction). The yaw written is that continuous value: at a key it equals
 * the file's yaw modulo 360 (exactly the file's value when consecutive file
 * yaws already differ by at most 180). Pitch is clamped to [-89, 89], and
 * the position to VRG_WORLD_LIMIT (the curve can overshoot keys at the edge).
 * A NULL or empty path leaves *inout untouched. */
void vrg_camera_path_eval(const vrg_camera_path *p, float time, vrg_camera *inout);
/* Time of the last key (paths play from t = 0; a path whose first key is
 * later holds that key until then). 0 for an empty path. */
float vrg_camera_path_duration(const vrg_camera_path *p);

#pragma GCC visibility pop

#ifdef __cplusplus
}
#endif
#endif

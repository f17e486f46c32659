/* See png_writer.h. One thread: PNG files of a sequence stay in order. */
#define _POSIX_C_SOURCE 200809L
#include "png_writer.h"
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include "util.h"
#include "voxrg/png.h"

typedef struct job {
    char path[VRG_CLI_PATH];
    vrg_image_data img;
} job;

struct vrg_cli_png_writer {
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t changed;
    job *jobs; /* a ring of depth */
    int depth, head, count;
    int closing, failed;
};

static void *run(void *arg)
{
    vrg_cli_png_writer *w = arg;
    pthread_mutex_lock(&w->lock);
    for (;;) {
        while (!w->count && !w->closing)
            pthread_cond_wait(&w->changed, &w->lock);
        if (!w->count)
            break;
        job j = w->jobs[w->head];
        pthread_mutex_unlock(&w->lock);
        int rc = vrg_write_png(j.path, &j.img); /* the encoding, outside the lock */
        free(j.img.pixels);
        pthread_mutex_lock(&w->lock);
        w->failed |= rc != 0;
        w->head = (w->head + 1) % w->depth;
        w->count--;
        pthread_cond_broadcast(&w->changed);
    }
    pthread_mutex_unlock(&w->lock);
    return NULL;
}

vrg_cli_png_writer *vrg_cli_png_writer_start(int depth)
{
    vrg_cli_png_writer *w = calloc(1, sizeof *w);
    job *jobs = calloc((size_t)depth, sizeof *jobs);
    if (!w || !jobs) {
        fprintf(stderr, "error: out of memory for the PNG writer\n");
        free(w), free(jobs);
        return NULL;
    }
    w->jobs = jobs;
    w->depth = depth;
    pthread_mutex_init(&w->lock, NULL);
    pthread_cond_init(&w->changed, NULL);
    int err = pthread_create(&w->thread, NULL, run, w);
    if (err) {
        fprintf(stderr, "error: cannot start the PNG writer thread: %s\n", strerror(err));
        pthread_mutex_destroy(&w->lock);
        pthread_cond_destroy(&w->changed);
        free(w->jobs), free(w);
        return NULL;
    }
    return w;
}

int vrg_cli_png_writer_push(vrg_cli_png_writer *w, const char *path, vrg_image_data *img)
{
    pthread_mutex_lock(&w->lock);
    while (w->count == w->depth && !w->failed)
        pthread_cond_wait(&w->changed, &w->lock);
    int failed = w->failed;
    if (!failed) {
        job *j = &w->jobs[(w->head + w->count) % w->depth];
        snprintf(j->path, sizeof j->path, "%s", path);
        j->img = *img;
        w->count++;
        pthread_cond_broadcast(&w->changed);
    }
    pthread_mutex_unlock(&w->lock);
    if (failed)
        free(img->pixels);
    img->pixels = NULL;
    return failed ? -1 : 0;
}

int vrg_cli_png_writer_finish(vrg_cli_png_writer *w)
{
    if (!w)
        return 0;
    pthread_mutex_lock(&w->lock);
    w->closing = 1;
    pthread_cond_broadcast(&w->changed);
    pthread_mutex_unlock(&w->lock);
    pthread_join(w->thread, NULL);
    int failed = w->failed;
    pthread_mutex_destroy(&w->lock);
    pthread_cond_destroy(&w->changed);
    free(w->jobs), free(w);
    return failed ? -1 : 0;
}

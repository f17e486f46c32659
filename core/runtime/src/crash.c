/* A fatal signal while plugin code runs names the plugin, its file, the pass
 * and the callback before the process ends: without it a bug in someone's
 * pass ends `voxrg render` with a bare "Segmentation fault".
 *
 * Plugin code runs only between _vrg_running_enter/leave (loading, check,
 * create, resize, execute, destroy, save/restore state); the handler reads
 * that thread's record, writes one line with write(2) (async-signal-safe),
 * removes a plugin copy that was being loaded, then puts back the handler
 * that was there before (the default, or a sanitizer's or the host's) and
 * returns: the faulting instruction runs again and that handler sees it, so
 * the process still dies of the same signal, or ASan still prints its
 * report. */
#define _GNU_SOURCE
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "internal.h"

static _Thread_local _vrg_running running;
static struct sigaction previous[NSIG];
static const int fatal_signals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
/* The private folder of a plugin being loaded (plugin_loader.c), removed if
 * its constructor or dlopen itself dies. Main thread only, like loading. */
static char loading_dir[VRG_PATH_MAX], loading_file[VRG_PATH_MAX];

static void put(const char *s)
{
    if (s)
        for (size_t n = strlen(s); n;) {
            ssize_t w = write(2, s, n);
            if (w <= 0)
                return;
            s += w, n -= (size_t)w;
        }
}

static const char *signal_name(int sig)
{
    switch (sig) {
    case SIGSEGV: return "SIGSEGV (invalid memory access)";
    case SIGBUS: return "SIGBUS (bus error)";
    case SIGFPE: return "SIGFPE (arithmetic error)";
    case SIGILL: return "SIGILL (illegal instruction)";
    case SIGABRT: return "SIGABRT (abort)";
    default: return "a fatal signal";
    }
}

static void on_fatal(int sig, siginfo_t *info, void *uc)
{
    (void)info, (void)uc;
    if (running.what) {
        put("\nvoxrg: ");
        put(signal_name(sig));
        if (running.pass) {
            put(" in pass '");
            put(running.pass);
            put("'");
        }
        put(" (plugin '");
        put(running.plugin);
        put("', ");
        put(running.file);
        put(") during ");
        put(running.what);
        put("\n");
    }
    if (loading_file[0])
        unlink(loading_file);
    if (loading_dir[0])
        rmdir(loading_dir);
    sigaction(sig, &previous[sig], NULL);
    /* a signal sent (abort(), kill) is not raised again by returning */
    if (info && info->si_code <= 0)
        raise(sig);
}

static void install(void)
{
    /* a stack overflow in a plugin must still reach the handler */
    static char alt[64 * 1024];
    stack_t ss = {.ss_sp = alt, .ss_size = sizeof alt};
    stack_t old;
    if (sigaltstack(NULL, &old) == 0 && (old.ss_flags & SS_DISABLE))
        sigaltstack(&ss, NULL);
    struct sigaction sa = {.sa_sigaction = on_fatal, .sa_flags = SA_SIGINFO | SA_ONSTACK};
    sigemptyset(&sa.sa_mask);
    for (size_t i = 0; i < sizeof fatal_signals / sizeof fatal_signals[0]; i++)
        sigaction(fatal_signals[i], &sa, &previous[fatal_signals[i]]);
}

_vrg_running _vrg_running_enter(const char *what, const char *pass, const _vrg_plugin *plugin)
{
    static int installed;
    if (!installed) {
        installed = 1;
        install();
    }
    _vrg_running before = running;
    running = (_vrg_running){.what = what, .pass = pass, .plugin = plugin->name, .file = plugin->source};
    return before;
}

void _vrg_running_leave(_vrg_running before) { running = before; }

void _vrg_crash_cleanup_set(const char *dir, const char *file)
{
    snprintf(loading_dir, sizeof loading_dir, "%s", dir ? dir : "");
    snprintf(loading_file, sizeof loading_file, "%s", file ? file : "");
}

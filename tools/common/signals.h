/* Ctrl-C and SIGTERM during a tool's long write: remove its temporary
 * output, say so in one line, exit 130 (SIGINT) or 143 (SIGTERM).
 *
 * For a tool's main file only: the state is static, one copy per tool, and
 * the library never sees it. The writers (partfile_write.c, write_ply.c)
 * build OUT.tmp and rename it over OUT only when complete, so an interrupted
 * run has nothing to undo but the temporary files: the handler unlinks the
 * registered paths, writes the prepared message and calls _exit, all
 * async-signal-safe. A previous OUT is never touched.
 */
#ifndef OIT_COMMON_SIGNALS_H
#define OIT_COMMON_SIGNALS_H

#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#define OIT_TOOL_TMP_MAX 3
#define OIT_TOOL_PATH_MAX 4096

static char oit_tool_tmp[OIT_TOOL_TMP_MAX][OIT_TOOL_PATH_MAX];
static char oit_tool_msg[2][2 * OIT_TOOL_PATH_MAX];

static void oit_tool_on_signal(int sig)
{
    for (int i = 0; i < OIT_TOOL_TMP_MAX; i++)
        if (oit_tool_tmp[i][0])
            unlink(oit_tool_tmp[i]);
    const char *m = oit_tool_msg[sig == SIGINT ? 0 : 1];
    ssize_t ignored = write(STDERR_FILENO, m, strlen(m));
    (void)ignored;
    _exit(128 + sig);
}

/* Registers out + each suffix (NULL-terminated, at most OIT_TOOL_TMP_MAX) as
 * the temporary files to remove and installs the handler for SIGINT and
 * SIGTERM. */
static inline void oit_tool_signals_install(const char *tool, const char *out,
                                            const char *const *suffixes)
{
    int n = 0;
    for (; suffixes[n] && n < OIT_TOOL_TMP_MAX; n++)
        snprintf(oit_tool_tmp[n], OIT_TOOL_PATH_MAX, "%s%s", out, suffixes[n]);
    static const char *const names[2] = {"SIGINT", "SIGTERM"};
    for (int k = 0; k < 2; k++)
        snprintf(oit_tool_msg[k], sizeof oit_tool_msg[k],
                 "%s: %s: interrupted by %s: temporary %s removed, %s not written (a "
                 "previous one is unchanged)\n",
                 tool, out, names[k], oit_tool_tmp[0], out);
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = oit_tool_on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

#endif

/* How a tool shows progress on stderr: a bar redrawn in place when stderr
 * is a terminal, else periodic lines (a pipe or a log would pile up the
 * bar's carriage returns and show nothing until the end). The environment
 * variable OIT_PROGRESS_PERIOD sets the seconds between lines (default 5;
 * the tests set it small to see lines from tiny inputs). */
#ifndef OIT_COMMON_PROGRESS_MODE_H
#define OIT_COMMON_PROGRESS_MODE_H

typedef struct oit_tool_progress {
    int bar;         /* 1: stderr is a terminal */
    double period_s; /* OIT_PROGRESS_PERIOD; 0 when unset (the default) */
} oit_tool_progress;

/* tool names the tool in the note for a malformed OIT_PROGRESS_PERIOD
 * (which is then ignored). */
oit_tool_progress oit_tool_progress_get(const char *tool);

#endif

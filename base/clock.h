/* The monotonic clock every timing in the project reads: phases of a frame,
 * conversion progress, decode rates. Not wall-clock time: it never jumps. */
#ifndef OIT_BASE_CLOCK_H
#define OIT_BASE_CLOCK_H

/* Milliseconds since an arbitrary fixed point. */
double oit_time_ms(void);

/* The same clock in seconds. */
double oit_time_s(void);

#endif

/*
 * stc_port.h - the RTOS port layer of the real-time harness (stc_rt_main.c).
 *
 * Everything the harness needs from an operating system: a monotonic clock,
 * sleeping until an absolute time, one lock, and periodic tasks with
 * priorities. stc_port_posix.c implements it with POSIX threads; a FreeRTOS
 * or uC/OS-II port is one file implementing these six functions.
 */
#ifndef STC_PORT_H
#define STC_PORT_H

#include <stdint.h>

/* Monotonic time in nanoseconds. */
int64_t stc_port_now_ns(void);

/* Sleeps until the monotonic time `t_ns` (returns at once if it passed). */
void stc_port_sleep_until(int64_t t_ns);

/* The lock around the program's data: one task runs programs at a time. */
void stc_port_lock(void);
void stc_port_unlock(void);

/* Starts `fn(arg)` as a task of IEC priority `priority` (0 is the most
   urgent). Returns 0 on success; `*realtime` is set to 1 when the task got
   real-time scheduling, 0 when it fell back to normal scheduling. */
int stc_port_task_start(void (*fn)(void *arg), void *arg, uint32_t priority, int *realtime);

/* Waits until every started task has returned. */
void stc_port_join_all(void);

#endif

/*
 * stc_port_posix.c - the port layer (stc_port.h) for POSIX: threads with
 * SCHED_FIFO when permitted, CLOCK_MONOTONIC, clock_nanosleep with
 * TIMER_ABSTIME.
 */
#define _POSIX_C_SOURCE 200809L

#include <pthread.h>
#include <sched.h>
#include <stddef.h>
#include <stdint.h>
#include <time.h>

#include "stc_port.h"

#define STC_PORT_MAX_TASKS 64

typedef struct {
    void (*fn)(void *arg);
    void *arg;
} stc_port_start;

static pthread_t stc_port_threads[STC_PORT_MAX_TASKS];
static stc_port_start stc_port_starts[STC_PORT_MAX_TASKS];
static uint32_t stc_port_n_threads = 0U;
static pthread_mutex_t stc_port_mutex = PTHREAD_MUTEX_INITIALIZER;

int64_t stc_port_now_ns(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return ((int64_t)ts.tv_sec * INT64_C(1000000000)) + (int64_t)ts.tv_nsec;
}

void stc_port_sleep_until(int64_t t_ns)
{
    struct timespec ts;
    int rc;
    ts.tv_sec = (time_t)(t_ns / INT64_C(1000000000));
    ts.tv_nsec = (long)(t_ns % INT64_C(1000000000));
    do {
        rc = clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL);
    } while (rc != 0);
}

void stc_port_lock(void)
{
    (void)pthread_mutex_lock(&stc_port_mutex);
}

void stc_port_unlock(void)
{
    (void)pthread_mutex_unlock(&stc_port_mutex);
}

static void *stc_port_trampoline(void *p)
{
    const stc_port_start *s = (const stc_port_start *)p;
    s->fn(s->arg);
    return NULL;
}

int stc_port_task_start(void (*fn)(void *arg), void *arg, uint32_t priority, int *realtime)
{
    int rc = -1;
    if (stc_port_n_threads < (uint32_t)STC_PORT_MAX_TASKS) {
        uint32_t k = stc_port_n_threads;
        pthread_attr_t attr;
        struct sched_param sp;
        int lo = sched_get_priority_min(SCHED_FIFO);
        int hi = sched_get_priority_max(SCHED_FIFO);
        int prio = hi - 1 - (int)((priority > 50U) ? 50U : priority);
        stc_port_starts[k].fn = fn;
        stc_port_starts[k].arg = arg;
        if (prio < lo) {
            prio = lo;
        }
        sp.sched_priority = prio;
        *realtime = 0;
        (void)pthread_attr_init(&attr);
        if ((pthread_attr_setinheritsched(&attr, PTHREAD_EXPLICIT_SCHED) == 0)
            && (pthread_attr_setschedpolicy(&attr, SCHED_FIFO) == 0)
            && (pthread_attr_setschedparam(&attr, &sp) == 0)) {
            rc = pthread_create(&stc_port_threads[k], &attr, stc_port_trampoline, &stc_port_starts[k]);
            if (rc == 0) {
                *realtime = 1;
            }
        }
        (void)pthread_attr_destroy(&attr);
        if (rc != 0) {
            /* Not permitted (no CAP_SYS_NICE): normal scheduling. */
            rc = pthread_create(&stc_port_threads[k], NULL, stc_port_trampoline, &stc_port_starts[k]);
        }
        if (rc == 0) {
            stc_port_n_threads = k + 1U;
        }
    }
    return rc;
}

void stc_port_join_all(void)
{
    uint32_t k;
    for (k = 0U; k < stc_port_n_threads; k++) {
        (void)pthread_join(stc_port_threads[k], NULL);
    }
    stc_port_n_threads = 0U;
}

/*
 * stc_rt_main.c - the real-time harness (seed 000 section IV.E-F).
 *
 * Every TASK of the chosen configuration becomes a task of the port layer
 * (stc_port.h: POSIX threads with SCHED_FIFO when permitted), released
 * periodically at absolute times; event tasks (SINGLE) are sampled every
 * millisecond and run on a rising edge; programs without a task run every
 * 10 ms at the lowest priority. Programs run one task at a time under the
 * port lock, with the process image exchanged around each cycle
 * (stc_io.h). Each program sees its task's nominal time as its clock, as
 * in simulation. Overruns (a cycle that ends after the next release) are
 * counted and reported; a fault stops the task's current cycle and is
 * reported, and the task goes on with its next cycle.
 *
 * Usage: rt [--cycles N] [--config NAME] [--max-steps N] [--quiet]
 * With --cycles N every periodic task runs N cycles, then the program
 * prints a summary and exits; without it, it runs until SIGINT.
 */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stc_io.h"
#include "stc_meta.h"
#include "stc_port.h"
#include "stc_rt.h"

#define STC_RT_MAX_TASKS 64U
#define STC_RT_EVENT_NS INT64_C(1000000)
#define STC_RT_FREE_NS INT64_C(10000000)

typedef struct {
    const char *name;
    const stc_task *task;             /* NULL: the task of free programs */
    const stc_program *programs[STC_RT_MAX_TASKS];
    uint32_t n_programs;
    int64_t interval_ns;              /* 0: an event task */
    uint32_t priority;
    uint64_t cycles;
    uint64_t overruns;
    uint64_t faults;
    int64_t max_exec_ns;
    uint8_t single_prev;
    int realtime;
} stc_rt_task;

static stc_rt_task stc_rt_tasks[STC_RT_MAX_TASKS];
static uint32_t stc_rt_n_tasks = 0U;
static uint64_t stc_rt_cycles = 0U;          /* 0: until SIGINT */
static uint64_t stc_rt_max_steps = UINT64_C(100000000);
static int stc_rt_quiet = 0;
static int64_t stc_rt_start = 0;
static volatile sig_atomic_t stc_rt_stop = 0;

static void stc_rt_on_sigint(int sig)
{
    (void)sig;
    stc_rt_stop = 1;
}

/* The elementary type of a descriptor (scalars, enumerations, subranges). */
static int stc_rt_elem(uint32_t t, uint8_t *e)
{
    int ok = 0;
    if (t < stc_n_types) {
        const stc_type *d = &stc_types[t];
        if ((d->kind == (uint8_t)STC_TK_SCALAR) || (d->kind == (uint8_t)STC_TK_ENUM)
            || (d->kind == (uint8_t)STC_TK_SUBRANGE)) {
            *e = d->elem;
            ok = 1;
        }
    }
    return ok;
}

/* Copies a connection's value, converting between elementary types. */
static uint32_t stc_rt_copy(const void *src, uint32_t st, void *dst, uint32_t dt)
{
    uint32_t fault = 0U;
    uint8_t se = 0U;
    uint8_t de = 0U;
    if ((st == dt) || (st >= stc_n_types) || (dt >= stc_n_types)) {
        if (st < stc_n_types) {
            (void)memcpy(dst, src, stc_types[st].size);
        }
    } else if ((stc_rt_elem(st, &se) != 0) && (stc_rt_elem(dt, &de) != 0)) {
        fault = stc_convert_scalar(se, src, de, dst);
    } else {
        (void)memcpy(dst, src, (stc_types[st].size < stc_types[dt].size)
                                   ? stc_types[st].size : stc_types[dt].size);
    }
    return fault;
}

/* Reports the pending fault at its site. */
static void stc_rt_report_site(void)
{
    if (stc_fault_site < stc_n_sites) {
        const stc_site *s = &stc_sites[stc_fault_site];
        (void)fprintf(stderr, "fault: %s in %s at %s:%u:%u\n", stc_fault_text(stc_fault_kind),
                      s->pou, s->file, (unsigned)s->line, (unsigned)s->col);
    }
}

/* Runs one program instance; returns non-zero after a fault. */
static int stc_rt_run_program(const stc_program *p)
{
    uint32_t k;
    uint32_t fault = 0U;
    for (k = 0U; (k < p->n_inputs) && (fault == 0U); k++) {
        const stc_conn *c = &p->inputs[k];
        fault = stc_rt_copy(c->data, c->data_type, (unsigned char *)p->data + c->inst_offset, c->type);
    }
    if (fault == 0U) {
        stc_fault_kind = 0U;
        p->body(p->data);
        fault = stc_fault_kind;
    }
    for (k = 0U; (k < p->n_outputs) && (fault == 0U); k++) {
        const stc_conn *c = &p->outputs[k];
        fault = stc_rt_copy((unsigned char *)p->data + c->inst_offset, c->type, c->data, c->data_type);
    }
    if (fault != 0U) {
        if ((stc_fault_kind != 0U) && (stc_fault_site < stc_n_sites)) {
            stc_rt_report_site();
        } else {
            (void)fprintf(stderr, "fault: %s in %s at <configuration>:0:0\n", stc_fault_text(fault),
                          p->name);
        }
    }
    return (fault != 0U) ? 1 : 0;
}

/* One cycle of a task at its nominal time, under the lock. */
static void stc_rt_cycle(stc_rt_task *t, int64_t nominal)
{
    uint32_t k;
    int64_t t0;
    int64_t dt;
    stc_port_lock();
    t0 = stc_port_now_ns();
    stc_io_inputs();
    stc_fault_kind = 0U;
    stc_image_read();
    if (stc_fault_kind != 0U) {
        /* A field value outside its variable's type: the programs do not
           run on it this cycle. */
        stc_rt_report_site();
        t->faults++;
    } else {
        stc_clock = nominal;
        stc_steps = stc_rt_max_steps;
        for (k = 0U; k < t->n_programs; k++) {
            if (stc_rt_run_program(t->programs[k]) != 0) {
                t->faults++;
                break;
            }
        }
    }
    stc_image_write();
    stc_io_outputs();
    dt = stc_port_now_ns() - t0;
    if (dt > t->max_exec_ns) {
        t->max_exec_ns = dt;
    }
    t->cycles++;
    stc_port_unlock();
}

static uint8_t stc_rt_single(const stc_task *task)
{
    uint8_t v = 0U;
    if ((task != NULL) && (task->single != NULL)) {
        (void)memcpy(&v, task->single, 1U);
    }
    return (v != 0U) ? 1U : 0U;
}

static void stc_rt_periodic(void *arg)
{
    stc_rt_task *t = (stc_rt_task *)arg;
    uint64_t k = 0U;
    int64_t period = (t->interval_ns > 0) ? t->interval_ns : STC_RT_EVENT_NS;
    while ((stc_rt_stop == 0) && ((stc_rt_cycles == 0U) || (k < stc_rt_cycles))) {
        int64_t release = stc_rt_start + ((int64_t)k * period);
        int64_t next = release + period;
        int run = 1;
        stc_port_sleep_until(release);
        if (t->interval_ns == 0) {
            /* An event task: runs on a rising edge of its SINGLE. */
            uint8_t v;
            stc_port_lock();
            /* The SINGLE may be a located input: sample the field. */
            stc_io_inputs();
            stc_image_read();
            stc_fault_kind = 0U;
            v = stc_rt_single(t->task);
            stc_port_unlock();
            run = 0;
            if ((v != 0U) && (t->single_prev == 0U)) {
                run = 1;
            }
            t->single_prev = v;
        }
        if (run != 0) {
            stc_rt_cycle(t, (int64_t)k * period);
        }
        if (stc_port_now_ns() > next) {
            t->overruns++;
            if (stc_rt_quiet == 0) {
                (void)fprintf(stderr, "warning: overrun: task %s cycle %llu\n", t->name,
                              (unsigned long long)(k + 1U));
            }
        }
        k++;
    }
}

static void stc_rt_add_program(stc_rt_task *t, const stc_program *p)
{
    if (t->n_programs < STC_RT_MAX_TASKS) {
        t->programs[t->n_programs] = p;
        t->n_programs++;
    }
}

static stc_rt_task *stc_rt_new_task(const char *name, const stc_task *task, int64_t interval,
                                    uint32_t priority)
{
    stc_rt_task *t = NULL;
    if (stc_rt_n_tasks < STC_RT_MAX_TASKS) {
        t = &stc_rt_tasks[stc_rt_n_tasks];
        stc_rt_n_tasks++;
        (void)memset(t, 0, sizeof *t);
        t->name = name;
        t->task = task;
        t->interval_ns = interval;
        t->priority = priority;
    }
    return t;
}

/* The tasks of a configuration, or the standalone programs. */
static int stc_rt_plan(const char *config)
{
    uint32_t c;
    uint32_t r;
    uint32_t k;
    uint32_t p;
    const stc_config *chosen = NULL;
    stc_rt_task *free_task = NULL;
    for (c = 0U; c < stc_n_configs; c++) {
        if ((config == NULL) || (strcmp(config, stc_configs[c].name) == 0)) {
            chosen = &stc_configs[c];
            break;
        }
    }
    if ((config != NULL) && (chosen == NULL)) {
        (void)fprintf(stderr, "error: no configuration `%s`\n", config);
        return 2;
    }
    if (chosen == NULL) {
        free_task = stc_rt_new_task("(programs)", NULL, STC_RT_FREE_NS, 1000U);
        for (p = 0U; (p < stc_n_programs) && (free_task != NULL); p++) {
            stc_rt_add_program(free_task, &stc_programs[p]);
        }
        return 0;
    }
    for (r = 0U; r < chosen->n_resources; r++) {
        const stc_resource *res = &chosen->resources[r];
        uint32_t first = stc_rt_n_tasks;
        for (k = 0U; k < res->n_tasks; k++) {
            const stc_task *task = &res->tasks[k];
            int64_t interval = (task->has_interval != 0U) ? task->interval_ns : 0;
            if ((interval == 0) && (task->single == NULL)) {
                interval = STC_RT_FREE_NS;
            }
            (void)stc_rt_new_task(task->name, task, interval, task->priority);
        }
        for (p = 0U; p < res->n_programs; p++) {
            const stc_program *prog = &res->programs[p];
            if ((prog->task >= 0) && ((first + (uint32_t)prog->task) < stc_rt_n_tasks)) {
                stc_rt_add_program(&stc_rt_tasks[first + (uint32_t)prog->task], prog);
            } else {
                if (free_task == NULL) {
                    free_task = stc_rt_new_task("(programs)", NULL, STC_RT_FREE_NS, 1000U);
                }
                if (free_task != NULL) {
                    stc_rt_add_program(free_task, prog);
                }
            }
        }
    }
    return 0;
}

/* A decimal count of an option. */
static uint64_t stc_rt_count(const char *text)
{
    errno = 0;
    uint64_t v = (uint64_t)strtoull(text, NULL, 10);
    if (errno != 0) {
        v = 0U;
    }
    return v;
}

int main(int argc, char **argv)
{
    int a = 1;
    int status = 0;
    uint32_t k;
    const char *config = NULL;
    while (a < argc) {
        int value = 0;
        if ((a + 1) < argc) {
            value = 1;
        }
        if ((strcmp(argv[a], "--cycles") == 0) && (value != 0)) {
            stc_rt_cycles = stc_rt_count(argv[a + 1]);
            a += 2;
        } else if ((strcmp(argv[a], "--config") == 0) && (value != 0)) {
            config = argv[a + 1];
            a += 2;
        } else if ((strcmp(argv[a], "--max-steps") == 0) && (value != 0)) {
            stc_rt_max_steps = stc_rt_count(argv[a + 1]);
            a += 2;
        } else if (strcmp(argv[a], "--quiet") == 0) {
            stc_rt_quiet = 1;
            a += 1;
        } else {
            (void)fprintf(stderr, "usage: rt [--cycles N] [--config NAME] [--max-steps N] [--quiet]\n");
            return 2;
        }
    }
    (void)signal(SIGINT, stc_rt_on_sigint);
    stc_init_all();
    status = stc_rt_plan(config);
    if (status != 0) {
        return status;
    }
    stc_rt_start = stc_port_now_ns() + INT64_C(1000000);
    for (k = 0U; k < stc_rt_n_tasks; k++) {
        stc_rt_task *t = &stc_rt_tasks[k];
        if (stc_port_task_start(stc_rt_periodic, t, t->priority, &t->realtime) != 0) {
            (void)fprintf(stderr, "error: cannot start task %s\n", t->name);
            stc_rt_stop = 1;
            status = 1;
        } else if ((t->realtime == 0) && (stc_rt_quiet == 0)) {
            (void)fprintf(stderr,
                          "warning: task %s runs with normal scheduling (SCHED_FIFO not permitted)\n",
                          t->name);
        } else {
            /* real-time scheduling, or quiet */
        }
    }
    stc_port_join_all();
    for (k = 0U; k < stc_rt_n_tasks; k++) {
        const stc_rt_task *t = &stc_rt_tasks[k];
        (void)printf("task %s: %llu cycles, %llu overruns, %llu faults, longest cycle %lld ns\n",
                     t->name, (unsigned long long)t->cycles, (unsigned long long)t->overruns,
                     (unsigned long long)t->faults, (long long)t->max_exec_ns);
        if (t->faults != 0U) {
            status = 3;
        }
    }
    return status;
}

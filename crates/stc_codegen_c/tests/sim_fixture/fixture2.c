/*
 * fixture2.c - a hand-written stand-in for the program.c generated from
 * fixture2.st: two configurations (so nothing runs by default), tasks
 * with INTERVAL and SINGLE, a task with neither, equal priorities over
 * two resources, and connections with a conversion.
 *
 * One deliberate difference from fixture2.st: the global `gb` is an LREAL
 * here (DINT in the ST source), so a value outside DINT makes the input
 * connection of `c1` fail, which the analyser never lets happen.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "stc_meta.h"
#include "stc_rt.h"

typedef struct {
    int16_t x;
} P_P1;

typedef struct {
    int32_t i;
    int32_t y;
} P_P2;

static int16_t g_ga;
static uint8_t g_trig;
static double g_gb;
static int32_t io_QD4; /* out_a */

static P_P1 i_a1;
static P_P2 i_a2;
static P_P1 i_a3;
static P_P2 i_b1;
static P_P1 i_b2;
static P_P2 i_c1;
static P_P1 s_p1;
static P_P2 s_p2;

enum { T_BOOL, T_INT, T_DINT, T_LREAL, T_P1, T_P2, T_COUNT };

static const stc_member p1_members[1] = {
    { "x", T_INT, offsetof(P_P1, x), STC_VK_OUTPUT, 0U, 0U, NULL }
};

static const stc_member p2_members[2] = {
    { "i", T_DINT, offsetof(P_P2, i), STC_VK_INPUT, 0U, 0U, NULL },
    { "y", T_DINT, offsetof(P_P2, y), STC_VK_OUTPUT, 0U, 0U, NULL }
};

#define SCALAR(e, ctype) { STC_TK_SCALAR, (e), 0U, 0U, NULL, 0U, NULL, NULL, NULL, 0U, 0U, sizeof(ctype), 0, 0 }

const stc_type stc_types[T_COUNT] = {
    SCALAR(STC_E_BOOL, uint8_t),
    SCALAR(STC_E_INT, int16_t),
    SCALAR(STC_E_DINT, int32_t),
    SCALAR(STC_E_LREAL, double),
    { STC_TK_INSTANCE, 0U, 0U, 0U, "P1", 1U, NULL, p1_members, NULL, 0U, 0U, sizeof(P_P1), 0, 0 },
    { STC_TK_INSTANCE, 0U, 0U, 0U, "P2", 2U, NULL, p2_members, NULL, 0U, 0U, sizeof(P_P2), 0, 0 }
};
const uint32_t stc_n_types = T_COUNT;

static int spend_step(uint32_t site)
{
    if (stc_steps == 0U) {
        stc_fault(STC_FAULT_WATCHDOG, site);
        return 0;
    }
    stc_steps--;
    return 1;
}

static void p1_body(void *p)
{
    P_P1 *self = (P_P1 *)p;
    uint16_t r;
    if (spend_step(0U) == 0) {
        return;
    }
    r = (uint16_t)((uint16_t)self->x + 1U);
    (void)memcpy(&self->x, &r, sizeof r);
}

static void p2_body(void *p)
{
    P_P2 *self = (P_P2 *)p;
    uint32_t r;
    if (spend_step(1U) == 0) {
        return;
    }
    r = (uint32_t)self->y + (uint32_t)self->i;
    (void)memcpy(&self->y, &r, sizeof r);
}

static const stc_task r1_tasks[2] = {
    { "both", 1U, 20000000, 1U, &g_trig, T_BOOL },
    { "none", 0U, 0, 3U, NULL, 0U }
};
static const stc_task r2_tasks[1] = { { "t5", 1U, 5000000, 1U, NULL, 0U } };

static const stc_conn ga_to_i[1] = { { offsetof(P_P2, i), T_DINT, &g_ga, T_INT } };
static const stc_conn y_to_out_a[1] = { { offsetof(P_P2, y), T_DINT, &io_QD4, T_DINT } };
static const stc_conn gb_to_i[1] = { { offsetof(P_P2, i), T_DINT, &g_gb, T_LREAL } };

static const stc_program r1_programs[3] = {
    { "a1", T_P1, &i_a1, p1_body, 0, NULL, 0U, NULL, 0U },
    { "a2", T_P2, &i_a2, p2_body, 1, ga_to_i, 1U, NULL, 0U },
    { "a3", T_P1, &i_a3, p1_body, 0, NULL, 0U, NULL, 0U }
};
static const stc_program r2_programs[2] = {
    { "b1", T_P2, &i_b1, p2_body, 0, ga_to_i, 1U, y_to_out_a, 1U },
    { "b2", T_P1, &i_b2, p1_body, -1, NULL, 0U, NULL, 0U }
};
static const stc_program r_programs[1] = { { "c1", T_P2, &i_c1, p2_body, -1, gb_to_i, 1U, NULL, 0U } };

static const stc_resource a_resources[2] = {
    { "R1", r1_tasks, 2U, r1_programs, 3U },
    { "R2", r2_tasks, 1U, r2_programs, 2U }
};
static const stc_resource b_resources[1] = { { "R", NULL, 0U, r_programs, 1U } };

const stc_config stc_configs[2] = { { "A", a_resources, 2U }, { "B", b_resources, 1U } };
const uint32_t stc_n_configs = 2U;

const stc_program stc_programs[2] = {
    { "P1", T_P1, &s_p1, p1_body, -1, NULL, 0U, NULL, 0U },
    { "P2", T_P2, &s_p2, p2_body, -1, NULL, 0U, NULL, 0U }
};
const uint32_t stc_n_programs = 2U;

const stc_global stc_globals[4] = {
    { "ga", T_INT, &g_ga, 0, NULL, 0U },
    { "trig", T_BOOL, &g_trig, 0, NULL, 0U },
    { "out_a", T_DINT, &io_QD4, 0, "%QD4", 0U },
    { "gb", T_LREAL, &g_gb, 1, NULL, 0U }
};
const uint32_t stc_n_globals = 4U;

const stc_io_slot stc_io[1] = { { "%QD4", &io_QD4, T_DINT } };
const uint32_t stc_n_io = 1U;

const stc_site stc_sites[2] = {
    { "P1", "tests/sim_fixture/fixture2.st", 5U, 3U },
    { "P2", "tests/sim_fixture/fixture2.st", 15U, 3U }
};
const uint32_t stc_n_sites = 2U;

void stc_init_all(void)
{
    g_ga = 2;
    g_trig = 0U;
    g_gb = 7.0;
    io_QD4 = 0;
    (void)memset(&i_a1, 0, sizeof i_a1);
    (void)memset(&i_a2, 0, sizeof i_a2);
    (void)memset(&i_a3, 0, sizeof i_a3);
    (void)memset(&i_b1, 0, sizeof i_b1);
    (void)memset(&i_b2, 0, sizeof i_b2);
    (void)memset(&i_c1, 0, sizeof i_c1);
    (void)memset(&s_p1, 0, sizeof s_p1);
    (void)memset(&s_p2, 0, sizeof s_p2);
}

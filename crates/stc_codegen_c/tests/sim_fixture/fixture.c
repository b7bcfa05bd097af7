/*
 * fixture.c - a hand-written stand-in for the program.c that
 * `stc build --emit c` generates from fixture.st: the same variables,
 * bodies and stc_meta.h tables, so the simulation harness (stc_sim*.c)
 * can be tested against `stc run fixture.st` before the generator exists.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "stc_meta.h"
#include "stc_rt.h"

/* ---- data ---------------------------------------------------------------- */

typedef struct {
    int16_t x;
    int16_t y;
} T_Point;

typedef struct {
    int16_t step;
    int32_t total;
    int16_t calls;
} FB_Acc;

typedef struct {
    uint8_t IN;
    int64_t PT;
    uint8_t Q;
    int64_t ET;
    int64_t start;
    uint8_t in_prev;
} FB_TON;

typedef struct {
    uint8_t start;
    int16_t divisor;
    int16_t count;
    float level;
    int16_t colour;
    FB_TON tmr;
    FB_Acc adder;
    int16_t arr[3];
    int32_t m[2][3];
    T_Point pt;
    T_Point pts[2];
    uint8_t name[2 + 10];
    uint16_t wname[1 + 5];
    uint8_t ch;
    uint16_t wch;
    double big;
    int64_t t;
    int64_t d;
    int64_t tod1;
    int64_t dt1;
    int16_t pct;
    uint8_t b;
    uint64_t u;
    void *lamp;
    void *sensor;
    void *g;
} P_Main;

typedef struct {
    int16_t inp;
    int16_t n;
} P_Aux;

/* globals and the process image */
static int16_t g_top;
static int16_t g_g;
static uint8_t g_trig;
static int8_t g_g_sint;
static int16_t g_K;
static uint8_t io_QX0_0; /* lamp_g */
static uint16_t io_IW2;  /* w_in */
static uint8_t io_QX1_0; /* Main.lamp */
static uint8_t io_IX0_0; /* Main.sensor */

/* program instances: the configuration's, then the standalone ones */
static P_Main i_main;
static P_Aux i_p2;
static P_Aux i_p3;
static P_Aux i_p4;
static P_Main s_main;
static P_Aux s_aux;

/* ---- types ----------------------------------------------------------------- */

enum {
    T_BOOL, T_INT, T_DINT, T_SINT, T_REAL, T_LREAL, T_TIME, T_DATE, T_TOD, T_DT, T_CHAR, T_WCHAR,
    T_BYTE, T_ULINT, T_WORD, T_COLOR, T_ARR, T_MAT, T_POINT, T_PTS, T_STR10, T_WSTR5, T_PCT,
    T_ACC, T_TON, T_MAIN, T_AUX, T_COUNT
};

static const stc_enum_value color_values[3] = { { "Red", 0 }, { "Green", 1 }, { "Blue", 2 } };
static const stc_dim arr_dims[1] = { { 1, 3 } };
static const stc_dim mat_dims[2] = { { 1, 2 }, { 0, 2 } };
static const stc_dim pts_dims[1] = { { 0, 1 } };

static const stc_member point_members[2] = {
    { "x", T_INT, offsetof(T_Point, x), STC_VK_FIELD, 0U, 0U, NULL },
    { "y", T_INT, offsetof(T_Point, y), STC_VK_FIELD, 0U, 0U, NULL }
};

static const stc_member acc_members[3] = {
    { "step", T_INT, offsetof(FB_Acc, step), STC_VK_INPUT, 0U, 0U, NULL },
    { "total", T_DINT, offsetof(FB_Acc, total), STC_VK_OUTPUT, 0U, 0U, NULL },
    { "calls", T_INT, offsetof(FB_Acc, calls), STC_VK_VAR, 0U, 0U, NULL }
};

static const stc_member ton_members[6] = {
    { "IN", T_BOOL, offsetof(FB_TON, IN), STC_VK_INPUT, 0U, 0U, NULL },
    { "PT", T_TIME, offsetof(FB_TON, PT), STC_VK_INPUT, 0U, 0U, NULL },
    { "Q", T_BOOL, offsetof(FB_TON, Q), STC_VK_OUTPUT, 0U, 0U, NULL },
    { "ET", T_TIME, offsetof(FB_TON, ET), STC_VK_OUTPUT, 0U, 0U, NULL },
    { "start", T_TIME, offsetof(FB_TON, start), STC_VK_VAR, 0U, 0U, NULL },
    { "in_prev", T_BOOL, offsetof(FB_TON, in_prev), STC_VK_VAR, 0U, 0U, NULL }
};

static const stc_member main_members[29] = {
    { "start", T_BOOL, offsetof(P_Main, start), STC_VK_INPUT, 0U, 0U, NULL },
    { "divisor", T_INT, offsetof(P_Main, divisor), STC_VK_INPUT, 0U, 0U, NULL },
    { "count", T_INT, offsetof(P_Main, count), STC_VK_OUTPUT, 0U, 0U, NULL },
    { "level", T_REAL, offsetof(P_Main, level), STC_VK_OUTPUT, 0U, 0U, NULL },
    { "colour", T_COLOR, offsetof(P_Main, colour), STC_VK_OUTPUT, 0U, 0U, NULL },
    { "tmr", T_TON, offsetof(P_Main, tmr), STC_VK_VAR, 0U, 0U, NULL },
    { "adder", T_ACC, offsetof(P_Main, adder), STC_VK_VAR, 0U, 0U, NULL },
    { "arr", T_ARR, offsetof(P_Main, arr), STC_VK_VAR, 0U, 0U, NULL },
    { "m", T_MAT, offsetof(P_Main, m), STC_VK_VAR, 0U, 0U, NULL },
    { "pt", T_POINT, offsetof(P_Main, pt), STC_VK_VAR, 0U, 0U, NULL },
    { "pts", T_PTS, offsetof(P_Main, pts), STC_VK_VAR, 0U, 0U, NULL },
    { "name", T_STR10, offsetof(P_Main, name), STC_VK_VAR, 0U, 0U, NULL },
    { "wname", T_WSTR5, offsetof(P_Main, wname), STC_VK_VAR, 0U, 0U, NULL },
    { "ch", T_CHAR, offsetof(P_Main, ch), STC_VK_VAR, 0U, 0U, NULL },
    { "wch", T_WCHAR, offsetof(P_Main, wch), STC_VK_VAR, 0U, 0U, NULL },
    { "big", T_LREAL, offsetof(P_Main, big), STC_VK_VAR, 0U, 0U, NULL },
    { "t", T_TIME, offsetof(P_Main, t), STC_VK_VAR, 0U, 0U, NULL },
    { "d", T_DATE, offsetof(P_Main, d), STC_VK_VAR, 0U, 0U, NULL },
    { "tod1", T_TOD, offsetof(P_Main, tod1), STC_VK_VAR, 0U, 0U, NULL },
    { "dt1", T_DT, offsetof(P_Main, dt1), STC_VK_VAR, 0U, 0U, NULL },
    { "pct", T_PCT, offsetof(P_Main, pct), STC_VK_VAR, 0U, 0U, NULL },
    { "b", T_BYTE, offsetof(P_Main, b), STC_VK_VAR, 0U, 0U, NULL },
    { "u", T_ULINT, offsetof(P_Main, u), STC_VK_VAR, 0U, 0U, NULL },
    { "lamp", T_BOOL, offsetof(P_Main, lamp), STC_VK_VAR, 1U, 0U, "%QX1.0" },
    { "sensor", T_BOOL, offsetof(P_Main, sensor), STC_VK_VAR, 1U, 0U, "%IX0.0" },
    { "g", T_INT, offsetof(P_Main, g), STC_VK_EXTERNAL, 1U, 0U, NULL },
    { "j", T_INT, 0U, STC_VK_TEMP, 0U, 0U, NULL },
    /* Not in the VM image: hidden variables must stay invisible. */
    { "_hidden", T_INT, offsetof(P_Main, count), STC_VK_HIDDEN, 0U, 0U, NULL },
    { "__unused", T_INT, offsetof(P_Main, count), STC_VK_HIDDEN, 0U, 0U, NULL }
};

static const stc_member aux_members[2] = {
    { "inp", T_INT, offsetof(P_Aux, inp), STC_VK_INPUT, 0U, 0U, NULL },
    { "n", T_INT, offsetof(P_Aux, n), STC_VK_OUTPUT, 0U, 0U, NULL }
};

#define SCALAR(e, ctype) { STC_TK_SCALAR, (e), 0U, 0U, NULL, 0U, NULL, NULL, NULL, 0U, 0U, sizeof(ctype), 0, 0 }

const stc_type stc_types[T_COUNT] = {
    SCALAR(STC_E_BOOL, uint8_t),
    SCALAR(STC_E_INT, int16_t),
    SCALAR(STC_E_DINT, int32_t),
    SCALAR(STC_E_SINT, int8_t),
    SCALAR(STC_E_REAL, float),
    SCALAR(STC_E_LREAL, double),
    SCALAR(STC_E_TIME, int64_t),
    SCALAR(STC_E_DATE, int64_t),
    SCALAR(STC_E_TOD, int64_t),
    SCALAR(STC_E_DT, int64_t),
    SCALAR(STC_E_CHAR, uint8_t),
    SCALAR(STC_E_WCHAR, uint16_t),
    SCALAR(STC_E_BYTE, uint8_t),
    SCALAR(STC_E_ULINT, uint64_t),
    SCALAR(STC_E_WORD, uint16_t),
    { STC_TK_ENUM, STC_E_INT, 0U, 0U, "Color", 3U, color_values, NULL, NULL, 0U, 0U, sizeof(int16_t), 0, 0 },
    { STC_TK_ARRAY, 0U, 0U, 0U, NULL, 1U, NULL, NULL, arr_dims, T_INT, sizeof(int16_t), 3U * sizeof(int16_t), 0, 0 },
    { STC_TK_ARRAY, 0U, 0U, 0U, NULL, 2U, NULL, NULL, mat_dims, T_DINT, sizeof(int32_t), 6U * sizeof(int32_t), 0, 0 },
    { STC_TK_STRUCT, 0U, 0U, 0U, "Point", 2U, NULL, point_members, NULL, 0U, 0U, sizeof(T_Point), 0, 0 },
    { STC_TK_ARRAY, 0U, 0U, 0U, NULL, 1U, NULL, NULL, pts_dims, T_POINT, sizeof(T_Point), 2U * sizeof(T_Point), 0, 0 },
    { STC_TK_STRING, 0U, 0U, 10U, NULL, 0U, NULL, NULL, NULL, 0U, 0U, 12U, 0, 0 },
    { STC_TK_STRING, 0U, 1U, 5U, NULL, 0U, NULL, NULL, NULL, 0U, 0U, 12U, 0, 0 },
    { STC_TK_SUBRANGE, STC_E_INT, 0U, 0U, NULL, 0U, NULL, NULL, NULL, 0U, 0U, sizeof(int16_t), 0, 100 },
    { STC_TK_INSTANCE, 0U, 0U, 0U, "Acc", 3U, NULL, acc_members, NULL, 0U, 0U, sizeof(FB_Acc), 0, 0 },
    { STC_TK_INSTANCE, 0U, 0U, 0U, "TON", 6U, NULL, ton_members, NULL, 0U, 0U, sizeof(FB_TON), 0, 0 },
    { STC_TK_INSTANCE, 0U, 0U, 0U, "Main", 29U, NULL, main_members, NULL, 0U, 0U, sizeof(P_Main), 0, 0 },
    { STC_TK_INSTANCE, 0U, 0U, 0U, "Aux", 2U, NULL, aux_members, NULL, 0U, 0U, sizeof(P_Aux), 0, 0 }
};
const uint32_t stc_n_types = T_COUNT;

/* ---- bodies ------------------------------------------------------------------ */

static int16_t add16(int16_t a, int16_t b)
{
    uint16_t r = (uint16_t)((uint16_t)a + (uint16_t)b);
    int16_t out;
    (void)memcpy(&out, &r, sizeof out);
    return out;
}

static int64_t wrap64(uint64_t u)
{
    int64_t out;
    (void)memcpy(&out, &u, sizeof out);
    return out;
}

static int32_t add32(int32_t a, int32_t b)
{
    uint32_t r = (uint32_t)a + (uint32_t)b;
    int32_t out;
    (void)memcpy(&out, &r, sizeof out);
    return out;
}

static uint8_t load_bool(const void *p)
{
    uint8_t v;
    (void)memcpy(&v, p, sizeof v);
    return v;
}

static void ton(FB_TON *self)
{
    if (self->IN == 0U) {
        self->Q = 0U;
        self->ET = 0;
    } else {
        if (self->in_prev == 0U) {
            self->start = stc_clock;
        }
        self->ET = stc_clock - self->start;
        if (self->ET >= self->PT) {
            self->ET = self->PT;
        }
        self->Q = (self->ET >= self->PT) ? 1U : 0U;
    }
    self->in_prev = self->IN;
}

static void acc(FB_Acc *self)
{
    self->total = add32(self->total, (int32_t)self->step);
    self->calls = add16(self->calls, 1);
}

/* The watchdog: one step at the start of a body (the VM counts
   instructions, so only a budget of 0 faults at the same place). */
static int spend_step(uint32_t site)
{
    if (stc_steps == 0U) {
        stc_fault(STC_FAULT_WATCHDOG, site);
        return 0;
    }
    stc_steps--;
    return 1;
}

static void main_body(void *p)
{
    P_Main *self = (P_Main *)p;
    int16_t *g = (int16_t *)self->g;
    int16_t j;
    uint16_t n;
    if (spend_step(1U) == 0) {
        return;
    }
    self->count = add16(self->count, 1);
    self->tmr.IN = ((self->start != 0U) || (load_bool(self->sensor) != 0U)) ? 1U : 0U;
    self->tmr.PT = 30000000;
    ton(&self->tmr);
    (void)memcpy(self->lamp, &self->tmr.Q, 1U);
    self->level = self->level + 0.1f;
    self->big = self->big * 3.0;
    self->adder.step = self->count;
    acc(&self->adder);
    j = (int16_t)(self->count % 3);
    if ((j < 0) || (j > 2)) {
        stc_fault(STC_FAULT_INDEX, 3U);
        return;
    }
    self->arr[j] = add16(self->arr[j], *g);
    self->m[1][j] = add32(self->m[1][j], self->adder.total);
    self->pts[j % 2].x = add16(self->pt.x, self->count);
    self->t = wrap64((uint64_t)self->t + 1500000000ULL);
    self->tod1 = (self->tod1 + 5400250000000LL) % 86400000000000LL;
    self->dt1 = wrap64((uint64_t)self->dt1 + 43200000000000ULL);
    if (self->pct < 100) {
        self->pct = add16(self->pct, 1);
    }
    self->b = (uint8_t)(self->b ^ 0x5AU);
    self->u += 1U;
    (void)memcpy(&n, self->name, sizeof n);
    if (n < 10U) {
        self->name[2U + n] = (uint8_t)'!';
        n++;
        (void)memcpy(self->name, &n, sizeof n);
    }
    self->colour = 1;
    *g = add16(*g, 1);
    if (self->divisor == 0) {
        stc_fault(STC_FAULT_DIVISION_BY_ZERO, 0U);
        return;
    }
    self->count = (int16_t)(self->count / self->divisor);
}

static void aux_body(void *p)
{
    P_Aux *self = (P_Aux *)p;
    if (spend_step(2U) == 0) {
        return;
    }
    self->n = add16(self->n, self->inp);
}

/* ---- configuration ---------------------------------------------------------- */

static const stc_task plant_tasks[3] = {
    { "fast", 1U, 10000000, 2U, NULL, 0U },
    { "slow", 1U, 30000000, 1U, NULL, 0U },
    { "ev", 0U, 0, 0U, &g_trig, T_BOOL }
};

static const stc_conn p2_inputs[1] = { { offsetof(P_Aux, inp), T_INT, &g_g, T_INT } };
static const stc_conn p2_outputs[1] = { { offsetof(P_Aux, n), T_INT, &g_top, T_INT } };
static const stc_conn p3_inputs[1] = { { offsetof(P_Aux, inp), T_INT, &g_g_sint, T_SINT } };

static const stc_program plant_programs[4] = {
    { "main", T_MAIN, &i_main, main_body, 0, NULL, 0U, NULL, 0U },
    { "p2", T_AUX, &i_p2, aux_body, 2, p2_inputs, 1U, p2_outputs, 1U },
    { "p3", T_AUX, &i_p3, aux_body, 1, p3_inputs, 1U, NULL, 0U },
    { "p4", T_AUX, &i_p4, aux_body, -1, NULL, 0U, NULL, 0U }
};

static const stc_resource plant_resources[1] = { { "Cpu", plant_tasks, 3U, plant_programs, 4U } };

const stc_config stc_configs[1] = { { "Plant", plant_resources, 1U } };
const uint32_t stc_n_configs = 1U;

const stc_program stc_programs[2] = {
    { "Main", T_MAIN, &s_main, main_body, -1, NULL, 0U, NULL, 0U },
    { "Aux", T_AUX, &s_aux, aux_body, -1, NULL, 0U, NULL, 0U }
};
const uint32_t stc_n_programs = 2U;

const stc_global stc_globals[7] = {
    { "top", T_INT, &g_top, -1, NULL, 0U },
    { "g", T_INT, &g_g, 0, NULL, 0U },
    { "lamp_g", T_BOOL, &io_QX0_0, 0, "%QX0.0", 0U },
    { "trig", T_BOOL, &g_trig, 0, NULL, 0U },
    { "g_sint", T_SINT, &g_g_sint, 0, NULL, 0U },
    { "w_in", T_WORD, &io_IW2, 0, "%IW2", 0U },
    { "K", T_INT, &g_K, 0, NULL, 1U }
};
const uint32_t stc_n_globals = 7U;

const stc_io_slot stc_io[4] = {
    { "%QX0.0", &io_QX0_0, T_BOOL },
    { "%IW2", &io_IW2, T_WORD },
    { "%QX1.0", &io_QX1_0, T_BOOL },
    { "%IX0.0", &io_IX0_0, T_BOOL }
};
const uint32_t stc_n_io = 4U;

const stc_site stc_sites[4] = {
    { "Main", "tests/sim_fixture/fixture.st", 91U, 3U },
    { "Main", "tests/sim_fixture/fixture.st", 66U, 3U },
    { "Aux", "tests/sim_fixture/fixture.st", 101U, 3U },
    { "Main", "tests/sim_fixture/fixture.st", 73U, 3U }
};
const uint32_t stc_n_sites = 4U;

static void init_main(P_Main *m)
{
    static const uint8_t hello[5] = { 'h', 'e', 'l', 'l', 'o' };
    uint16_t n = 5U;
    (void)memset(m, 0, sizeof *m);
    m->divisor = 1;
    m->arr[0] = 10;
    m->arr[1] = 20;
    m->arr[2] = 30;
    (void)memcpy(m->name, &n, sizeof n);
    (void)memcpy(&m->name[2], hello, sizeof hello);
    m->wname[0] = 2U;
    m->wname[1] = (uint16_t)'h';
    m->wname[2] = (uint16_t)'i';
    m->ch = (uint8_t)'A';
    m->big = 0.1;
    m->lamp = &io_QX1_0;
    m->sensor = &io_IX0_0;
    m->g = &g_g;
}

void stc_init_all(void)
{
    g_top = 0;
    g_g = 0;
    g_trig = 0U;
    g_g_sint = 0;
    g_K = 5;
    io_QX0_0 = 0U;
    io_IW2 = 0U;
    io_QX1_0 = 0U;
    io_IX0_0 = 0U;
    init_main(&i_main);
    init_main(&s_main);
    (void)memset(&i_p2, 0, sizeof i_p2);
    (void)memset(&i_p3, 0, sizeof i_p3);
    (void)memset(&i_p4, 0, sizeof i_p4);
    (void)memset(&s_aux, 0, sizeof s_aux);
}

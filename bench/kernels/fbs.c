#include <stdint.h>
#include <stdbool.h>
typedef struct { bool IN; int64_t PT; bool Q; int64_t ET; int64_t start; bool in_prev; } TON;
typedef struct { bool CU, R; int16_t PV; bool Q; int16_t CV; bool cu_prev; } CTU;
static int64_t now;
static void ton(TON *t) {
    if (!t->IN) { t->Q = false; t->ET = 0; }
    else {
        if (!t->in_prev) t->start = now;
        t->ET = now - t->start;
        if (t->ET >= t->PT) t->ET = t->PT;
        t->Q = t->ET >= t->PT;
    }
    t->in_prev = t->IN;
}
static void ctu(CTU *c) {
    if (c->R) c->CV = 0;
    else if (c->CU && !c->cu_prev && c->CV < 32767) c->CV++;
    c->cu_prev = c->CU;
    c->Q = c->CV >= c->PV;
}
static TON t[1001];
static CTU c[1001];
static bool toggle;
volatile int32_t out;
static void cycle(void) {
    toggle = !toggle;
    int32_t done = 0;
    for (int i = 1; i <= 1000; i++) {
        t[i].IN = toggle; t[i].PT = 20000000; ton(&t[i]);
        c[i].CU = toggle; c[i].R = false; c[i].PV = 100; ctu(&c[i]);
        if (t[i].Q || c[i].Q) done++;
    }
    out = done;
    now += 10000000;
}
#include "harness.h"

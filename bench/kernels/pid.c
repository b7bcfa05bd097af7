volatile float out;
static void cycle(void) {
    float y = 0.0f, i_term = 0.0f, prev_e = 0.0f, sp = 50.0f;
    for (int k = 1; k <= 1000; k++) {
        float e = sp - y;
        i_term = i_term + 0.01f * e;
        if (i_term > 100.0f) i_term = 100.0f;
        if (i_term < -100.0f) i_term = -100.0f;
        float d_term = (e - prev_e) * 0.5f;
        float u = 2.0f * e + i_term + d_term;
        prev_e = e;
        y = y + (u - y) * 0.05f;
    }
    out = y;
}
#include "harness.h"

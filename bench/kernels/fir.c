volatile double out;
static double h[32], x[1024], y[1024];
static void cycle(void) {
    for (int k = 0; k < 32; k++) h[k] = 1.0 / (double)(k + 1);
    for (int n = 0; n < 1024; n++) x[n] = (double)((n * 37) % 101) - 50.0;
    double sum = 0.0;
    for (int n = 31; n < 1024; n++) {
        double acc = 0.0;
        for (int k = 0; k < 32; k++) acc += h[k] * x[n - k];
        y[n] = acc;
        sum += acc;
    }
    out = sum;
}
#include "harness.h"

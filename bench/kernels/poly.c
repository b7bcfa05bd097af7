volatile double out;
static const double c[9] = {1.0, -0.5, 0.25, 0.125, -0.0625, 0.03125, 0.015625, -0.0078125, 0.00390625};
static void cycle(void) {
    double acc = 0.0;
    for (int k = 0; k <= 999; k++) {
        double x = (double)k * 0.001;
        double p = c[8];
        for (int j = 7; j >= 0; j--) p = p * x + c[j];
        acc = acc + p;
    }
    out = acc;
}
#include "harness.h"

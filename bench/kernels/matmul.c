volatile double out;
static double a[24][24], b[24][24], c[24][24];
static void cycle(void) {
    for (int i = 0; i < 24; i++)
        for (int j = 0; j < 24; j++) {
            a[i][j] = (double)(i + j) * 0.5;
            b[i][j] = (double)(i - j) * 0.25;
        }
    for (int i = 0; i < 24; i++)
        for (int j = 0; j < 24; j++) {
            double s = 0.0;
            for (int k = 0; k < 24; k++) s += a[i][k] * b[k][j];
            c[i][j] = s;
        }
    double trace = 0.0;
    for (int i = 0; i < 24; i++) trace += c[i][i];
    out = trace;
}
#include "harness.h"

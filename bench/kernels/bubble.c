#include <stdint.h>
volatile int32_t out;
static int32_t a[1001];
static void cycle(void) {
    for (int i = 1; i <= 1000; i++) a[i] = 1001 - i;
    for (int i = 1; i <= 999; i++) {
        for (int j = 1; j <= 1000 - i; j++) {
            if (a[j] > a[j + 1]) { int32_t t = a[j]; a[j] = a[j + 1]; a[j + 1] = t; }
        }
    }
    out = a[1];
}
#include "harness.h"

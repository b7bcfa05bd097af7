#include <stdint.h>
volatile int32_t out_first, out_last;
static int32_t a[1000];
static void cycle(void) {
    int32_t seed = 1;
    for (int i = 0; i < 1000; i++) {
        seed = (seed * 75 + 74) % 65537;
        a[i] = seed;
    }
    for (int i = 1; i < 1000; i++) {
        int32_t t = a[i];
        int j = i;
        while (j > 0 && a[j - 1] > t) {
            a[j] = a[j - 1];
            j--;
        }
        a[j] = t;
    }
    out_first = a[0];
    out_last = a[999];
}
#include "harness.h"

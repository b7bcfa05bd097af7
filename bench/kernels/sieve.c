#include <stdbool.h>
#include <stdint.h>
volatile int32_t out;
static bool flags[20000];
static void cycle(void) {
    for (int i = 0; i < 20000; i++) flags[i] = true;
    int32_t count = 0;
    for (int32_t i = 2; i < 20000; i++) {
        if (flags[i]) {
            count++;
            for (int32_t j = i * i; j < 20000; j += i) flags[j] = false;
        }
    }
    out = count;
}
#include "harness.h"

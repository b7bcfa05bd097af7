/* Same work as sum.st: the C baseline. */
#include <stdint.h>
volatile int32_t out;
static void cycle(void) {
    int32_t s = 0;
    for (int32_t i = 1; i <= 10000; i++) {
        s = (int32_t)((uint32_t)s + (uint32_t)(i * 3) - (uint32_t)(i % 7));
    }
    out = s;
}
#include "harness.h"

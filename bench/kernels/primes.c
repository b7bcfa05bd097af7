#include <stdint.h>
volatile int32_t out;
static void cycle(void) {
    int32_t count = 0;
    for (int32_t n = 2; n <= 4999; n++) {
        int prime = 1;
        for (int32_t d = 2; d * d <= n; d++) {
            if (n % d == 0) { prime = 0; break; }
        }
        if (prime) count++;
    }
    out = count;
}
#include "harness.h"

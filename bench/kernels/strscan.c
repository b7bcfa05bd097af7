#include <stdint.h>
volatile int32_t out_words, out_digits, out_check;
static unsigned char text[4096];
static int ready;
static void cycle(void) {
    if (!ready) {
        for (int i = 0; i < 4096; i++) {
            if (i % 7 == 6) text[i] = ' ';
            else if (i % 5 == 0) text[i] = (unsigned char)('0' + i % 10);
            else text[i] = (unsigned char)('a' + i % 26);
        }
        ready = 1;
    }
    int32_t words = 0, digits = 0, check = 0;
    int inword = 0;
    for (const unsigned char *p = text; p < text + sizeof text; p++) {
        unsigned char c = *p;
        if (c == ' ') {
            inword = 0;
        } else {
            if (!inword) { words++; inword = 1; }
            if (c >= '0' && c <= '9') digits++;
        }
        check = (check * 31 + c) % 1000003;
    }
    out_words = words;
    out_digits = digits;
    out_check = check;
}
#include "harness.h"

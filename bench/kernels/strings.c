#include <stdio.h>
#include <string.h>
volatile int out;
static void cycle(void) {
    int found = 0;
    char s[81], part[11];
    for (int k = 1; k <= 100; k++) {
        char num[8];
        snprintf(num, sizeof num, "%d", k);
        snprintf(s, sizeof s, "pump-%s", num);
        strncat(s, "-running", sizeof s - strlen(s) - 1);
        if (strstr(s, "run") != NULL) found++;
        memcpy(part, s + 1, 4);
        part[4] = 0;
        if (strcmp(part, "ump-") == 0) found++;
    }
    out = found;
}
#include "harness.h"

/*
 * fmt_driver.c - test driver for the value formats of the simulation
 * harness (stc_sim_text.c): reads lines `r HEX32` (a REAL's bits) or
 * `l HEX64` (an LREAL's), `t NS` (TIME), `d SECS` (DATE), `o NS` (TOD),
 * `a NS` (DT), and prints `TEXT\tJSON` for each, so the Rust test can
 * compare them with stc_runtime's report formats.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stc_sim.h"

int main(void)
{
    char line[128];
    sim_buf out;
    sim_buf_init(&out);
    while (fgets(line, sizeof line, stdin) != NULL) {
        char kind = line[0];
        sim_buf_clear(&out);
        if ((kind == 'r') || (kind == 'l')) {
            unsigned long long bits = strtoull(&line[2], NULL, 16);
            double x;
            if (kind == 'r') {
                uint32_t b32 = (uint32_t)bits;
                float f;
                memcpy(&f, &b32, sizeof f);
                x = (double)f;
            } else {
                uint64_t b64 = (uint64_t)bits;
                memcpy(&x, &b64, sizeof x);
            }
            sim_fmt_real(&out, x, (kind == 'r') ? 1 : 0, 0);
            sim_putc(&out, '\t');
            sim_fmt_real(&out, x, (kind == 'r') ? 1 : 0, 1);
        } else {
            int64_t v = (int64_t)strtoll(&line[2], NULL, 10);
            if (kind == 't') {
                sim_fmt_duration(&out, v, 0);
            } else if (kind == 'd') {
                sim_fmt_date(&out, v, 0);
            } else if (kind == 'o') {
                sim_fmt_tod(&out, v, 0);
            } else {
                sim_fmt_dt(&out, v, 0);
            }
        }
        sim_putc(&out, '\n');
        fwrite(out.p, 1, out.len, stdout);
    }
    sim_buf_free(&out);
    return 0;
}

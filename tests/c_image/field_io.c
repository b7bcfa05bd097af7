/*
 * A test's field I/O for process_image.st: the inputs of each cycle are
 * written into the image arrays as raw bits, and the output arrays are
 * printed after each cycle (crates/stc/tests/c_backend.rs checks them).
 */
#include <stdio.h>

#include "stc_io.h"
#include "program.h"

static unsigned calls = 0U;

void stc_io_inputs(void)
{
    static const uint8_t pct[4] = { 42U, 200U, 50U, 50U };
    static const uint16_t mode[4] = { 7U, 7U, 5U, 3U };
    unsigned k = (calls < 4U) ? calls : 3U;
    calls++;
    stc_img_I_X[1][4] = 1U;
    stc_img_I_W[0][2] = 0xFFFBU;               /* INT -5 */
    stc_img_I_D[0][3] = 0x3FC00000UL;          /* REAL 1.5 */
    stc_img_I_L[1][0][2] = 0x4004000000000000ULL; /* LREAL 2.5 */
    stc_img_I_L[0][0][0] = 2000000000ULL;      /* T#2s */
    stc_img_I_B[3] = pct[k];                   /* USINT(0..100) */
    stc_img_I_W[1][1] = mode[k];               /* Mode: 0, 3 or 7 */
}

void stc_io_outputs(void)
{
    (void)printf("out X=%u B=%02x W=%04x K=%04x D=%08lx L1=%016llx L2=%llu\n",
                 (unsigned)stc_img_Q_X[5][2], (unsigned)stc_img_Q_B[7],
                 (unsigned)stc_img_Q_W[2][5], (unsigned)stc_img_Q_W[0][9],
                 (unsigned long)stc_img_Q_D[0],
                 (unsigned long long)stc_img_Q_L[1], (unsigned long long)stc_img_Q_L[2]);
}

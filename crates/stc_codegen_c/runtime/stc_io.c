/*
 * stc_io.c - field I/O for the real-time harness: fill in these two
 * functions for your hardware (keep your copy outside the generated
 * directory and build with `make rt IO=path/to/your_io.c`). This default
 * connects nothing: inputs keep their initial values (stc_init_all writes
 * them into the input arrays), outputs go nowhere.
 */
#include "stc_io.h"
#include "program.h"

void stc_io_inputs(void)
{
    /* Example, for a program with a located %IX1.4 and a digital input
       card 1 at some memory address:
           stc_img_I_X[1][4] = ((card1_register & 0x10U) != 0U) ? 1U : 0U; */
}

void stc_io_outputs(void)
{
    /* Example, for a program with a located %QW2.5:
           analog_out_card2[5] = stc_img_Q_W[2][5]; */
}

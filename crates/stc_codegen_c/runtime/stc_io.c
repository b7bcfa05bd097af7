/*
 * stc_io.c - field I/O for the real-time harness: fill in these two
 * functions for your hardware (keep your copy outside the generated
 * directory and build with `make rt IO=path/to/your_io.c`). This default
 * connects nothing: inputs keep their values, outputs go nowhere.
 */
#include "stc_io.h"
#include "stc_meta.h"

void stc_io_inputs(void)
{
    /* Example: for each k < stc_n_io whose address starts with "%I",
       write the field value into *(type *)stc_io[k].data. */
}

void stc_io_outputs(void)
{
    /* Example: for each k < stc_n_io whose address starts with "%Q",
       read *(type *)stc_io[k].data and drive the field. */
}

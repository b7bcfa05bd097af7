/*
 * stc_io.h - the process image and the field: the one place an integrator
 * connects real I/O. The real-time harness calls stc_io_inputs() before a
 * task's programs run and stc_io_outputs() after, holding the program lock.
 * The slots are the entries of stc_io[] (stc_meta.h): each has its IEC
 * address ("%IX0.3", "%QW2"...), a pointer to its variable and its type.
 */
#ifndef STC_IO_H
#define STC_IO_H

/* Copies the field inputs into the %I slots of stc_io[]. */
void stc_io_inputs(void);

/* Copies the %Q slots of stc_io[] out to the field. */
void stc_io_outputs(void);

#endif

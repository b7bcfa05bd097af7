/*
 * stc_io.h - the process image and the field: the one place an integrator
 * connects real I/O (seed 000 section IV.C).
 *
 * The field side of the process image is a set of plain unsigned arrays,
 * one per area and size used by the program, declared in program.h:
 * %IX1.4 is stc_img_I_X[1][4], %QW2.5 is stc_img_Q_W[2][5] (uint8_t for
 * X and B, uint16_t for W, uint32_t for D, uint64_t for L; an address with
 * fewer parts than the longest of its array is padded with leading zeros:
 * %IW3 beside %IW1.4 is stc_img_I_W[0][3]). A bit element is 0 or 1; a
 * word holds the bits of its variable (two's complement, IEC 60559 for
 * REAL/LREAL), so the integrator never deals with ST types.
 *
 * Each cycle of a task, holding the program lock, the real-time harness
 * calls stc_io_inputs(), copies the input arrays into the program's
 * located variables (stc_image_read, stc_meta.h), runs the task's
 * programs, copies the located outputs into the output arrays
 * (stc_image_write) and calls stc_io_outputs(). The event-task sampler
 * also calls stc_io_inputs() every millisecond, under the lock.
 */
#ifndef STC_IO_H
#define STC_IO_H

/* Reads the field inputs into the stc_img_I_* arrays. */
void stc_io_inputs(void);

/* Drives the field outputs from the stc_img_Q_* arrays. */
void stc_io_outputs(void);

#endif

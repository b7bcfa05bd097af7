/*
 * stc_gen.h - small helpers the generated program.c uses for what is not
 * an operation on values: string assignment and constants, array index
 * checks, bits of bit strings, and the watchdog step. All are static inline
 * so the C compiler sees through them.
 */
#ifndef STC_GEN_H
#define STC_GEN_H

#include <stdint.h>
#include <string.h>

#include "stc_rt.h"

/* ---- strings ------------------------------------------------------------ */

/* (String assignment is stc_str_copy / stc_wstr_copy of stc_rt.h.) */

/* Sets a STRING array to a constant (the bytes are Windows-1252). */
static inline void stc_sconst(uint8_t *dst, const uint8_t *bytes, uint16_t n)
{
    (void)memcpy(dst, (const uint8_t *)&n, sizeof n);
    (void)memcpy(&dst[2], bytes, (size_t)n);
}

/* Sets a WSTRING array to a constant (UTF-16 units). */
static inline void stc_wsconst(uint16_t *dst, const uint16_t *units, uint16_t n)
{
    dst[0] = n;
    (void)memcpy(&dst[1], units, (size_t)n * sizeof(uint16_t));
}

/* ---- array indices ---------------------------------------------------- */

/* The zero-based position of index i in lo..hi, or a fault (and 0). */
static inline uint32_t stc_ix_i64(int64_t i, int64_t lo, int64_t hi, uint32_t site)
{
    uint32_t k = 0U;
    if ((i < lo) || (i > hi)) {
        stc_fault_range((uint32_t)STC_FAULT_INDEX, site, (uint64_t)i, (uint64_t)lo, (uint64_t)hi,
                        0U);
    } else {
        k = (uint32_t)((uint64_t)i - (uint64_t)lo);
    }
    return k;
}

/* The same for an unsigned 64-bit index (beyond INT64_MAX is out of range). */
static inline uint32_t stc_ix_u64(uint64_t i, int64_t lo, int64_t hi, uint32_t site)
{
    uint32_t k = 0U;
    if (i > (uint64_t)INT64_MAX) {
        stc_fault_range((uint32_t)STC_FAULT_INDEX, site, i, (uint64_t)lo, (uint64_t)hi,
                        1U /* the value is unsigned */);
    } else {
        k = stc_ix_i64((int64_t)i, lo, hi, site);
    }
    return k;
}

/* ---- bits of bit strings (x.%X3, x.%B1 ...) ----------------------------- */

/* Part `index` of `bits` bits of a word. */
static inline uint64_t stc_getpart(uint64_t word, uint32_t bits, uint32_t index)
{
    uint64_t mask = (bits >= 64U) ? UINT64_MAX : ((UINT64_C(1) << bits) - 1U);
    uint32_t shift = index * bits;
    return (shift >= 64U) ? 0U : ((word >> shift) & mask);
}

/* The word with part `index` of `bits` bits replaced by `v`. */
static inline uint64_t stc_setpart(uint64_t word, uint32_t bits, uint32_t index, uint64_t v)
{
    uint64_t mask = (bits >= 64U) ? UINT64_MAX : ((UINT64_C(1) << bits) - 1U);
    uint32_t shift = index * bits;
    uint64_t r = word;
    if (shift < 64U) {
        r = (word & ~(mask << shift)) | ((v & mask) << shift);
    }
    return r;
}

/* ---- the watchdog ------------------------------------------------------- */

/* One step of the watchdog budget (loop iterations and calls); with
   STC_WATCHDOG undefined it costs nothing. Returns non-zero on a fault. */
static inline uint32_t stc_step(uint32_t site)
{
#ifdef STC_WATCHDOG
    uint32_t out = 0U;
    if (stc_steps == 0U) {
        stc_fault((uint32_t)STC_FAULT_WATCHDOG, site);
        out = 1U;
    } else {
        stc_steps--;
    }
    return out;
#else
    (void)site;
    return 0U;
#endif
}

/* After a call of a POU that cannot fault: only the watchdog can have
   stopped it (never, without STC_WATCHDOG). */
static inline uint32_t stc_watchdog_tripped(void)
{
#ifdef STC_WATCHDOG
    return (stc_fault_kind != 0U) ? 1U : 0U;
#else
    return 0U;
#endif
}

#endif

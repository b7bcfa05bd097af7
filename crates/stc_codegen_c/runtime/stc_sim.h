/*
 * stc_sim.h - internal interface of the simulation harness (stc_sim*.c).
 *
 * The harness is a port of crates/stc_runtime (and of the option parsing
 * of `stc run`): it reads the descriptor tables of stc_meta.h where the
 * Rust runtime reads the VM image, and prints the same reports, messages
 * and exit statuses. It is host-side test tooling, not part of the
 * generated program.
 */
#ifndef STC_SIM_H
#define STC_SIM_H

#include <stddef.h>
#include <stdint.h>

#include "stc_meta.h"

/* ---- memory and text buffers (stc_sim_text.c) ------------------------- */

/* A growable byte buffer; the text is UTF-8 and kept NUL-terminated. */
typedef struct {
    char *p;
    size_t len;
    size_t cap;
} sim_buf;

void *sim_alloc(size_t n);
void *sim_grow(void *p, size_t count, size_t size);
char *sim_strndup(const char *s, size_t n);

void sim_buf_init(sim_buf *b);
void sim_buf_free(sim_buf *b);
void sim_buf_clear(sim_buf *b);
void sim_put(sim_buf *b, const char *s, size_t n);
void sim_puts(sim_buf *b, const char *s);
void sim_putc(sim_buf *b, char c);
void sim_put_u64(sim_buf *b, uint64_t v);
void sim_put_i64(sim_buf *b, int64_t v);
/* `v` in decimal, zero-padded to `width` characters (sign included), as
   Rust's `{:0width$}`. */
void sim_put_i64_padded(sim_buf *b, int64_t v, size_t width);

/* ---- UTF-8 and characters (stc_sim_text.c) ---------------------------- */

/* The code point at s[0..n) (n >= 1) and its length; an invalid sequence
   counts as one byte standing for U+FFFD. */
size_t sim_utf8_next(const char *s, size_t n, uint32_t *cp);
/* Whether s[0..n) is UTF-8 as Rust's str accepts it. */
int sim_utf8_valid(const char *s, size_t n);
void sim_put_utf8(sim_buf *b, uint32_t cp);
/* Appends s[0..n), each invalid sequence replaced by U+FFFD (Rust's
   from_utf8_lossy). */
void sim_put_lossy(sim_buf *b, const char *s, size_t n);
size_t sim_char_count(const char *s, size_t n);
int sim_is_space(uint32_t cp);
/* Rust's str::trim: strips Unicode White_Space at both ends. */
void sim_trim(const char **s, size_t *n);
/* ASCII case-insensitive equality (eq_ignore_ascii_case). */
int sim_ieq(const char *a, size_t an, const char *b, size_t bn);
int sim_ieq_z(const char *a, size_t an, const char *z);
uint32_t sim_cp1252_decode(uint8_t b);
/* The Windows-1252 byte of a code point, or -1. */
int sim_cp1252_encode(uint32_t cp);

/* ---- value formats (stc_sim_text.c) ----------------------------------- */

void sim_fmt_duration(sim_buf *b, int64_t ns, int long_form);
void sim_fmt_date(sim_buf *b, int64_t secs, int long_form);
void sim_fmt_tod(sim_buf *b, int64_t ns, int long_form);
void sim_fmt_dt(sim_buf *b, int64_t ns, int long_form);
/* A REAL (`single`, x holds a float) or LREAL: `json` selects serde_json's
   form (shortest round trip, "NaN"/"INF" strings), else the ST literal
   form of stc_values::to_text. */
void sim_fmt_real(sim_buf *b, double x, int single, int json);
/* A JSON string literal of UTF-8 text. */
void sim_json_string(sim_buf *b, const char *s, size_t n);
/* An ST string literal of the code points cps[0..n) (format_string). */
void sim_st_string(sim_buf *b, const uint32_t *cps, size_t n, int wide);

/* ---- types and values (stc_sim_value.c) ------------------------------- */

/* What a place holds: a type, or the rows an index left of a
   multi-dimensional array (`m[2]` of `m[1..3, 1..4]`). */
typedef struct {
    int slice;
    uint32_t type;          /* the type, or the element type of a slice */
    const stc_dim *dims;    /* slice: the dimensions left */
    uint32_t ndims;
    size_t stride;
} sim_view;

/* A value read from text, in memory representation. */
typedef struct {
    union {
        int64_t i;
        uint64_t u;
        double d;
        unsigned char b[16];
    } scalar;
    size_t size;            /* bytes of a scalar */
    int is_string;
    int wide;
    uint8_t *s;             /* STRING bytes */
    uint16_t *w;            /* WSTRING units */
    size_t len;
} sim_value;

const stc_type *sim_type(uint32_t t);
/* The elementary type of a scalar, subrange or enumeration type, or -1. */
int sim_scalar_of(uint32_t t);
size_t sim_elem_size(int elem);
const char *sim_elem_name(int elem);
/* The name of a type for messages (path.rs `describe`). */
void sim_describe(sim_buf *b, uint32_t t);
/* Appends the value at `addr` (NULL: unreadable) in the text or JSON form. */
void sim_emit_value(sim_buf *out, int json, const unsigned char *addr, const sim_view *v);
/* Reads `text` as a value for a place (value.rs `parse_for`). */
int sim_parse_for(const sim_view *v, const char *text, size_t n, sim_value *out, sim_buf *err);
void sim_value_free(sim_value *v);
/* Writes a value where a place of view `v` is; 0 when it cannot. */
int sim_write_value(unsigned char *addr, const sim_view *v, const sim_value *val);
/* Reads a value as an integer (BOOL and integer-like types); 0 when the
   type has none. */
int sim_read_int(int elem, const unsigned char *p, int64_t *i, uint64_t *u, int *is_unsigned);

/* ---- paths (stc_sim_path.c) -------------------------------------------- */

typedef struct {
    uint8_t deref;
    size_t add;
} sim_step;

/* A resolved variable (or part of one). */
typedef struct {
    sim_buf name;           /* declared spelling */
    unsigned char *base;
    sim_step *steps;
    size_t nsteps;
    sim_view view;
    int constant;
} sim_place;

/* What paths resolve against: the program instances that run and the
   chosen configuration (-1: none). */
typedef struct {
    const stc_program *const *inst;
    size_t ninst;
    int32_t config;
} sim_scope;

int sim_resolve(const sim_scope *sc, const char *text, size_t n, sim_place *out, sim_buf *err);
void sim_place_free(sim_place *p);
/* Where the place is now, following references; NULL when a reference
   is NULL. */
unsigned char *sim_place_addr(const sim_place *p);
/* Splits a --watch list at the commas outside brackets; items are
   trimmed, empty ones dropped. Returns the number of items; items[i] is
   heap text. */
size_t sim_split_list(const char *text, size_t n, char ***items);
/* The default watch list (sim.rs `default_watch`). */
size_t sim_default_watch(const sim_scope *sc, sim_place **out);
/* The area letter ('I', 'Q', 'M') of a location text, or 0. */
char sim_location_area(const char *loc);

/* ---- stimulus files (stc_sim_stim.c) ----------------------------------- */

/* A piece of text with its length (it may hold NUL characters). */
typedef struct {
    char *p;                /* NULL: none */
    size_t n;
} sim_text;

typedef struct {
    size_t line;
    uint64_t cycle;
    sim_text *cells;        /* one per column; p == NULL leaves it alone */
} sim_row;

typedef struct {
    sim_text *columns;
    size_t ncols;
    size_t header_line;
    sim_row *rows;
    size_t nrows;
} sim_stimulus;

/* Parses a stimulus file's text; on error `err` gets the message and
   `*line` its 1-based line. */
int sim_stimulus_parse(const char *text, size_t n, sim_stimulus *st, size_t *line, sim_buf *err);
void sim_stimulus_free(sim_stimulus *st);

#endif

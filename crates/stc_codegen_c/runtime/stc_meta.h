/*
 * stc_meta.h - descriptor tables of a generated program: the program model
 * with C addresses. The real-time harness (stc_rt_main.c) schedules tasks
 * from them; `stc run --backend c` (crates/stc_engine_c) reads them from
 * the program built as a shared library and runs it with stc's runtime.
 *
 * The tables are the program model (crates/stc_ir/src/model.rs), in its
 * numbering (a type's index here is its index in the model and in the VM's
 * .stbc file; the first types are the instance types of every POU, in POU
 * order), with C addresses instead of the model's data-area offsets: an offset here is a byte offset from the
 * start of the enclosing object (offsetof), and a reference variable
 * (is_ref) holds a C pointer (void *) to the real variable.
 *
 * Value representation in memory (shared with stc_rt.h):
 *   BOOL: uint8_t 0/1; SINT..LINT: int8_t..int64_t; USINT..ULINT, BYTE..LWORD:
 *   uint8_t..uint64_t; REAL: float; LREAL: double; CHAR: uint8_t (a
 *   Windows-1252 byte); WCHAR: uint16_t (UTF-16 unit); TIME, LTIME: int64_t
 *   nanoseconds; DATE, LDATE: int64_t seconds since 1970-01-01 (a multiple of
 *   86400); TOD, LTOD: int64_t nanoseconds since midnight; DT, LDT: int64_t
 *   nanoseconds since 1970-01-01T00:00:00; STRING[n]: uint8_t[2 + n], the
 *   length (0..n) in the first two bytes as a native uint16_t, then the
 *   bytes; WSTRING[n]: uint16_t[1 + n], the length in element 0;
 *   enumerations: their base integer type.
 */
#ifndef STC_META_H
#define STC_META_H

#include <stddef.h>
#include <stdint.h>

/* The codes of elementary types (STC_E_*), type descriptor kinds
   (STC_TK_*), variable kinds (STC_VK_*) and faults (STC_FAULT_*), written
   from the Rust definitions. */
#include "stc_codes.h"

typedef struct {
    const char *name;       /* as declared */
    int64_t value;
} stc_enum_value;

typedef struct {
    int64_t lo;
    int64_t hi;
} stc_dim;

/* A struct field or a variable of an instance. */
typedef struct {
    const char *name;       /* as declared */
    uint32_t type;          /* index in stc_types */
    size_t offset;          /* offsetof in the struct or instance */
    uint8_t kind;           /* enum stc_var_kind */
    uint8_t in_frame;       /* lives in a call's frame (no offset here) */
    uint8_t is_ref;         /* the member holds a void * to the variable */
    uint8_t constant;       /* declared CONSTANT */
    uint8_t retain;         /* declared RETAIN */
    const char *location;   /* "%QX0.0" for a located variable, else NULL */
} stc_member;

typedef struct {
    uint8_t kind;                   /* enum stc_type_kind */
    uint8_t elem;                   /* enum stc_elem: SCALAR, ENUM, SUBRANGE;
                                       INSTANCE: enum stc_pou_kind */
    uint8_t wide;                   /* STRING: 1 for WSTRING */
    uint32_t cap;                   /* STRING: capacity in characters */
    const char *name;               /* ENUM, STRUCT, INSTANCE */
    uint32_t count;                 /* entries of values, members or dims */
    const stc_enum_value *values;   /* ENUM */
    const stc_member *members;      /* STRUCT, INSTANCE */
    const stc_dim *dims;            /* ARRAY */
    uint32_t elem_type;             /* ARRAY: element type index */
    size_t stride;                  /* ARRAY: sizeof one element */
    size_t size;                    /* sizeof a whole value */
    int64_t lo;                     /* SUBRANGE */
    int64_t hi;
} stc_type;

/* A program connection: `inst_offset` in the instance, with its type,
   and the global (or process image slot) `data` of type `data_type`. */
typedef struct {
    size_t inst_offset;
    uint32_t type;
    void *data;
    uint32_t data_type;
} stc_conn;

typedef struct {
    const char *name;               /* instance name as declared */
    uint32_t type;                  /* its INSTANCE type */
    void *data;                     /* the instance */
    void (*body)(void *self);       /* one run of the program body */
    int32_t task;                   /* index in its resource's tasks, -1: none */
    const stc_conn *inputs;         /* copied in before the body runs */
    uint32_t n_inputs;
    const stc_conn *outputs;        /* copied out after it */
    uint32_t n_outputs;
} stc_program;

typedef struct {
    const char *name;
    uint8_t has_interval;
    int64_t interval_ns;
    uint32_t priority;
    void *single;                   /* the SINGLE variable, or NULL */
    uint32_t single_type;
} stc_task;

typedef struct {
    const char *name;               /* NULL for an unnamed resource */
    const stc_task *tasks;
    uint32_t n_tasks;
    const stc_program *programs;
    uint32_t n_programs;
} stc_resource;

typedef struct {
    const char *name;
    const stc_resource *resources;
    uint32_t n_resources;
} stc_config;

typedef struct {
    const char *name;
    uint32_t type;
    void *data;
    int32_t config;                 /* index in stc_configs, -1: top level */
    const char *location;           /* "%IX0.0" or NULL */
    uint8_t constant;
    uint8_t retain;                 /* declared RETAIN */
} stc_global;

typedef struct {
    const char *address;            /* "%QX0.0" */
    void *data;
    uint32_t type;
} stc_io_slot;

/* Where a fault can happen: the statement's POU and source position. */
typedef struct {
    const char *pou;
    const char *file;
    uint32_t line;
    uint32_t col;
} stc_site;

extern const stc_type stc_types[];
extern const uint32_t stc_n_types;
extern const stc_config stc_configs[];
extern const uint32_t stc_n_configs;
/* A standalone instance of every PROGRAM type (for --program). */
extern const stc_program stc_programs[];
extern const uint32_t stc_n_programs;
extern const stc_global stc_globals[];
extern const uint32_t stc_n_globals;
extern const stc_io_slot stc_io[];
extern const uint32_t stc_n_io;
extern const stc_site stc_sites[];
extern const uint32_t stc_n_sites;

/* Sets every global, instance and process image slot to its initial value
   (a fresh machine). */
void stc_init_all(void);

/* The field's process image (program.h declares its arrays, stc_img_I_X,
   stc_img_Q_W, ...: seed 000's DV__I_X[card][channel]). stc_image_read
   copies the %I arrays into the located input variables (an input out of
   its subrange or enumeration is a fault, STC_FAULT_SUBRANGE, and is not
   copied); stc_image_write copies the located output variables into the
   %Q arrays. */
void stc_image_read(void);
void stc_image_write(void);

#endif

/*
 * stc_codes.h - the numeric codes shared by the generated C, its runtime
 * and the Rust side of stc. Written by stc (stc_codegen_c::codes) from
 * the Rust enumerations that define them; do not edit.
 */
#ifndef STC_CODES_H
#define STC_CODES_H

/* Elementary types (stc_syntax::token::ElemType). */
enum {
    STC_E_BOOL = 0,
    STC_E_SINT = 1,
    STC_E_INT = 2,
    STC_E_DINT = 3,
    STC_E_LINT = 4,
    STC_E_USINT = 5,
    STC_E_UINT = 6,
    STC_E_UDINT = 7,
    STC_E_ULINT = 8,
    STC_E_REAL = 9,
    STC_E_LREAL = 10,
    STC_E_BYTE = 11,
    STC_E_WORD = 12,
    STC_E_DWORD = 13,
    STC_E_LWORD = 14,
    STC_E_TIME = 15,
    STC_E_LTIME = 16,
    STC_E_DATE = 17,
    STC_E_LDATE = 18,
    STC_E_TOD = 19,
    STC_E_LTOD = 20,
    STC_E_DT = 21,
    STC_E_LDT = 22,
    STC_E_STRING = 23,
    STC_E_WSTRING = 24,
    STC_E_CHAR = 25,
    STC_E_WCHAR = 26
};

/* Kinds of type descriptors (stc_ir::model::TypeDescKind). */
enum {
    STC_TK_SCALAR = 0,
    STC_TK_STRING = 1,
    STC_TK_ENUM = 2,
    STC_TK_ARRAY = 3,
    STC_TK_STRUCT = 4,
    STC_TK_INSTANCE = 5,
    STC_TK_SUBRANGE = 6
};

/* Kinds of variables (stc_ir::model::VarKind); STC_VK_FIELD: a member of a STRUCT. */
enum {
    STC_VK_INPUT = 0,
    STC_VK_OUTPUT = 1,
    STC_VK_INOUT = 2,
    STC_VK_VAR = 3,
    STC_VK_TEMP = 4,
    STC_VK_EXTERNAL = 5,
    STC_VK_GLOBAL = 6,
    STC_VK_RESULT = 7,
    STC_VK_HIDDEN = 8,
    STC_VK_FIELD = 9
};

/* Kinds of POUs (stc_ir::model::PouKind), in the elem of an INSTANCE type. */
enum {
    STC_PK_FUNCTION = 0,
    STC_PK_FUNCTION_BLOCK = 1,
    STC_PK_PROGRAM = 2
};

/* Fault kinds (stc_ir::FaultKind); the texts are in stc_fault_text().
   STC_N_FAULT_KINDS: the number of codes, STC_FAULT_NONE included. */
enum {
    STC_FAULT_NONE = 0,
    STC_FAULT_DIVISION_BY_ZERO = 1,
    STC_FAULT_INDEX = 2,
    STC_FAULT_SUBRANGE = 3,
    STC_FAULT_CONVERSION = 4,
    STC_FAULT_MUX = 5,
    STC_FAULT_FOR_STEP_ZERO = 6,
    STC_FAULT_WATCHDOG = 7,
    STC_FAULT_INVALID_CODE = 8,
    STC_FAULT_NULL_REFERENCE = 9,
    STC_FAULT_POINTER_BOUNDS = 10,
    STC_N_FAULT_KINDS = 11
};

#endif

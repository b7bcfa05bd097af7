/*
 * stc_sim_value.c - values of variables in both directions (a port of
 * stc_runtime's value.rs and report.rs): printed from memory in the text
 * or JSON form of reports, and read from ST literal text for `--set` and
 * stimulus cells.
 */
#include "stc_sim.h"

#include <stdlib.h>
#include <string.h>

#include "stc_rt.h"

/* How deep types may nest before reading gives up (value.rs MAX_DEPTH). */
#define SIM_MAX_DEPTH 64U

const stc_type *sim_type(uint32_t t)
{
    return (t < stc_n_types) ? &stc_types[t] : NULL;
}

int sim_scalar_of(uint32_t t)
{
    const stc_type *d = sim_type(t);
    if ((d != NULL) &&
        ((d->kind == (uint8_t)STC_TK_SCALAR) || (d->kind == (uint8_t)STC_TK_ENUM) ||
         (d->kind == (uint8_t)STC_TK_SUBRANGE))) {
        return (int)d->elem;
    }
    return -1;
}

size_t sim_elem_size(int elem)
{
    switch (elem) {
    case STC_E_BOOL:
    case STC_E_SINT:
    case STC_E_USINT:
    case STC_E_BYTE:
    case STC_E_CHAR:
        return 1U;
    case STC_E_INT:
    case STC_E_UINT:
    case STC_E_WORD:
    case STC_E_WCHAR:
        return 2U;
    case STC_E_DINT:
    case STC_E_UDINT:
    case STC_E_DWORD:
    case STC_E_REAL:
        return 4U;
    case STC_E_STRING:
    case STC_E_WSTRING:
        return 0U;
    default:
        return 8U;
    }
}

const char *sim_elem_name(int elem)
{
    static const char *const names[] = {
        /* In the order of enum stc_elem (stc_meta.h). */
        "BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT", "REAL", "LREAL",
        "BYTE", "WORD", "DWORD", "LWORD", "TIME", "LTIME", "DATE", "LDATE", "TOD", "LTOD", "DT",
        "LDT", "STRING", "WSTRING", "CHAR", "WCHAR"
    };
    if ((elem >= 0) && ((size_t)elem < (sizeof names / sizeof names[0]))) {
        return names[elem];
    }
    return "?";
}

void sim_describe(sim_buf *b, uint32_t t)
{
    const stc_type *d = sim_type(t);
    if (d == NULL) {
        sim_puts(b, "an unknown type");
        return;
    }
    switch (d->kind) {
    case STC_TK_SCALAR:
        sim_puts(b, sim_elem_name((int)d->elem));
        break;
    case STC_TK_SUBRANGE:
        sim_puts(b, sim_elem_name((int)d->elem));
        sim_puts(b, " (");
        sim_put_i64(b, d->lo);
        sim_puts(b, "..");
        sim_put_i64(b, d->hi);
        sim_putc(b, ')');
        break;
    case STC_TK_STRING:
        sim_puts(b, (d->wide != 0U) ? "WSTRING[" : "STRING[");
        sim_put_u64(b, d->cap);
        sim_putc(b, ']');
        break;
    case STC_TK_ENUM:
        sim_puts(b, (d->name != NULL) ? d->name : "?");
        break;
    case STC_TK_ARRAY:
        sim_puts(b, "ARRAY");
        break;
    case STC_TK_STRUCT:
        sim_puts(b, (d->name != NULL) ? d->name : "STRUCT");
        break;
    case STC_TK_INSTANCE:
        sim_puts(b, (d->name != NULL) ? d->name : "an instance");
        break;
    default:
        sim_puts(b, "an unknown type");
        break;
    }
}

/* ---- reading ------------------------------------------------------------- */

int sim_read_int(int elem, const unsigned char *p, int64_t *i, uint64_t *u, int *is_unsigned)
{
    *i = 0;
    *u = 0U;
    *is_unsigned = 0;
    switch (elem) {
    case STC_E_BOOL:
        *i = (p[0] != 0U) ? 1 : 0;
        return 1;
    case STC_E_SINT: {
        int8_t v;
        (void)memcpy(&v, p, sizeof v);
        *i = v;
        return 1;
    }
    case STC_E_INT: {
        int16_t v;
        (void)memcpy(&v, p, sizeof v);
        *i = v;
        return 1;
    }
    case STC_E_DINT: {
        int32_t v;
        (void)memcpy(&v, p, sizeof v);
        *i = v;
        return 1;
    }
    case STC_E_LINT:
    case STC_E_TIME:
    case STC_E_LTIME:
    case STC_E_DATE:
    case STC_E_LDATE:
    case STC_E_TOD:
    case STC_E_LTOD:
    case STC_E_DT:
    case STC_E_LDT: {
        int64_t v;
        (void)memcpy(&v, p, sizeof v);
        *i = v;
        return 1;
    }
    case STC_E_USINT:
    case STC_E_BYTE:
    case STC_E_CHAR:
        *u = p[0];
        *is_unsigned = 1;
        return 1;
    case STC_E_UINT:
    case STC_E_WORD:
    case STC_E_WCHAR: {
        uint16_t v;
        (void)memcpy(&v, p, sizeof v);
        *u = v;
        *is_unsigned = 1;
        return 1;
    }
    case STC_E_UDINT:
    case STC_E_DWORD: {
        uint32_t v;
        (void)memcpy(&v, p, sizeof v);
        *u = v;
        *is_unsigned = 1;
        return 1;
    }
    case STC_E_ULINT:
    case STC_E_LWORD: {
        uint64_t v;
        (void)memcpy(&v, p, sizeof v);
        *u = v;
        *is_unsigned = 1;
        return 1;
    }
    default:
        return 0;
    }
}

static void emit_unreadable(sim_buf *out, int json)
{
    sim_puts(out, (json != 0) ? "null" : "?");
}

/* A character (report.rs char_of) as text or JSON. */
static void emit_char(sim_buf *out, int json, uint32_t code, int wide)
{
    uint32_t cp;
    if ((wide == 0) && (code <= 0xFFU)) {
        cp = sim_cp1252_decode((uint8_t)code);
    } else if ((code > 0x10FFFFU) || ((code >= 0xD800U) && (code <= 0xDFFFU))) {
        cp = 0xFFFDU;
    } else {
        cp = code;
    }
    if (json != 0) {
        sim_buf t;
        sim_buf_init(&t);
        sim_put_utf8(&t, cp);
        sim_json_string(out, t.p, t.len);
        sim_buf_free(&t);
    } else {
        sim_st_string(out, &cp, 1U, wide);
    }
}

static void emit_scalar(sim_buf *out, int json, int elem, const unsigned char *p)
{
    int64_t i;
    uint64_t u;
    int is_unsigned;
    sim_buf t;
    if (elem == STC_E_REAL) {
        float f;
        (void)memcpy(&f, p, sizeof f);
        sim_fmt_real(out, (double)f, 1, json);
        return;
    }
    if (elem == STC_E_LREAL) {
        double d;
        (void)memcpy(&d, p, sizeof d);
        sim_fmt_real(out, d, 0, json);
        return;
    }
    if (sim_read_int(elem, p, &i, &u, &is_unsigned) == 0) {
        emit_unreadable(out, json);
        return;
    }
    switch (elem) {
    case STC_E_BOOL:
        if (json != 0) {
            sim_puts(out, (i != 0) ? "true" : "false");
        } else {
            sim_puts(out, (i != 0) ? "TRUE" : "FALSE");
        }
        return;
    case STC_E_CHAR:
    case STC_E_WCHAR:
        emit_char(out, json, (uint32_t)u, (elem == STC_E_WCHAR) ? 1 : 0);
        return;
    case STC_E_TIME:
    case STC_E_LTIME:
    case STC_E_DATE:
    case STC_E_LDATE:
    case STC_E_TOD:
    case STC_E_LTOD:
    case STC_E_DT:
    case STC_E_LDT:
        sim_buf_init(&t);
        if ((elem == STC_E_TIME) || (elem == STC_E_LTIME)) {
            sim_fmt_duration(&t, i, (elem == STC_E_LTIME) ? 1 : 0);
        } else if ((elem == STC_E_DATE) || (elem == STC_E_LDATE)) {
            sim_fmt_date(&t, i, (elem == STC_E_LDATE) ? 1 : 0);
        } else if ((elem == STC_E_TOD) || (elem == STC_E_LTOD)) {
            sim_fmt_tod(&t, i, (elem == STC_E_LTOD) ? 1 : 0);
        } else {
            sim_fmt_dt(&t, i, (elem == STC_E_LDT) ? 1 : 0);
        }
        if (json != 0) {
            sim_json_string(out, t.p, t.len);
        } else {
            sim_put(out, t.p, t.len);
        }
        sim_buf_free(&t);
        return;
    default:
        if (is_unsigned != 0) {
            sim_put_u64(out, u);
        } else {
            sim_put_i64(out, i);
        }
        return;
    }
}

static void emit_string(sim_buf *out, int json, const stc_type *d, const unsigned char *p)
{
    uint16_t len;
    size_t n;
    size_t k;
    size_t i;
    uint32_t *cps;
    (void)memcpy(&len, p, sizeof len);
    n = ((uint32_t)len < d->cap) ? (size_t)len : (size_t)d->cap;
    cps = (uint32_t *)sim_alloc((n + 1U) * sizeof(uint32_t));
    k = 0U;
    if (d->wide == 0U) {
        for (i = 0U; i < n; i++) {
            cps[k] = sim_cp1252_decode(p[2U + i]);
            k++;
        }
    } else {
        /* UTF-16, unpaired surrogates as U+FFFD (from_utf16_lossy). */
        i = 0U;
        while (i < n) {
            uint16_t a;
            (void)memcpy(&a, &p[2U + (2U * i)], sizeof a);
            if ((a >= 0xD800U) && (a <= 0xDBFFU) && ((i + 1U) < n)) {
                uint16_t c;
                (void)memcpy(&c, &p[2U + (2U * (i + 1U))], sizeof c);
                if ((c >= 0xDC00U) && (c <= 0xDFFFU)) {
                    cps[k] = 0x10000U + ((((uint32_t)a - 0xD800U) << 10) | ((uint32_t)c - 0xDC00U));
                    k++;
                    i += 2U;
                    continue;
                }
            }
            cps[k] = ((a >= 0xD800U) && (a <= 0xDFFFU)) ? 0xFFFDU : (uint32_t)a;
            k++;
            i++;
        }
    }
    if (json != 0) {
        sim_buf t;
        sim_buf_init(&t);
        for (i = 0U; i < k; i++) {
            sim_put_utf8(&t, cps[i]);
        }
        sim_json_string(out, t.p, t.len);
        sim_buf_free(&t);
    } else {
        sim_st_string(out, cps, k, (d->wide != 0U) ? 1 : 0);
    }
    free(cps);
}

static void emit_type(sim_buf *out, int json, const unsigned char *p, uint32_t t, unsigned depth);

static uint64_t dim_len(const stc_dim *d)
{
    if (d->hi < d->lo) {
        return 0U;
    }
    return ((uint64_t)d->hi - (uint64_t)d->lo) + 1U;
}

static void emit_array(sim_buf *out, int json, const unsigned char *p, uint32_t elem,
                       const stc_dim *dims, uint32_t ndims, size_t stride, unsigned depth)
{
    uint64_t len;
    uint64_t row = 1U;
    uint64_t i;
    uint32_t k;
    if (ndims == 0U) {
        emit_type(out, json, p, elem, depth + 1U);
        return;
    }
    len = dim_len(&dims[0]);
    for (k = 1U; k < ndims; k++) {
        row *= dim_len(&dims[k]);
    }
    row *= (uint64_t)stride;
    sim_putc(out, '[');
    for (i = 0U; i < len; i++) {
        if (i > 0U) {
            sim_puts(out, (json != 0) ? "," : ", ");
        }
        emit_array(out, json, (p != NULL) ? &p[(size_t)(i * row)] : NULL, elem, &dims[1], ndims - 1U,
                   stride, depth + 1U);
    }
    sim_putc(out, ']');
}

/* Whether a variable of a POU is shown as a member of its instance
   (path.rs is_member): inputs, outputs, VAR, located variables. */
static int is_member(const stc_member *m)
{
    return (m->kind == (uint8_t)STC_VK_INPUT) || (m->kind == (uint8_t)STC_VK_OUTPUT) ||
           (m->kind == (uint8_t)STC_VK_VAR) || (m->kind == (uint8_t)STC_VK_GLOBAL);
}

static void emit_record(sim_buf *out, int json, const unsigned char *p, const stc_type *d, unsigned depth)
{
    uint32_t k;
    int first = 1;
    int instance = (d->kind == (uint8_t)STC_TK_INSTANCE) ? 1 : 0;
    sim_putc(out, (json != 0) ? '{' : '(');
    for (k = 0U; k < d->count; k++) {
        const stc_member *m = &d->members[k];
        const unsigned char *a = &p[m->offset];
        if ((instance != 0) && (is_member(m) == 0)) {
            continue;
        }
        if (first == 0) {
            sim_puts(out, (json != 0) ? "," : ", ");
        }
        first = 0;
        if (json != 0) {
            sim_json_string(out, m->name, strlen(m->name));
            sim_putc(out, ':');
        } else {
            sim_puts(out, m->name);
            sim_puts(out, " := ");
        }
        if ((instance != 0) && (m->is_ref != 0U)) {
            void *q;
            (void)memcpy(&q, a, sizeof q);
            a = (const unsigned char *)q;
        }
        emit_type(out, json, a, m->type, depth + 1U);
    }
    sim_putc(out, (json != 0) ? '}' : ')');
}

static void emit_enum(sim_buf *out, int json, const unsigned char *p, const stc_type *d)
{
    int64_t i;
    uint64_t u;
    int is_unsigned;
    uint32_t k;
    if ((d->elem == (uint8_t)STC_E_BOOL) ||
        (sim_read_int((int)d->elem, p, &i, &u, &is_unsigned) == 0)) {
        emit_unreadable(out, json);
        return;
    }
    for (k = 0U; k < d->count; k++) {
        const stc_enum_value *v = &d->values[k];
        int same = (is_unsigned != 0) ? ((v->value >= 0) && ((uint64_t)v->value == u)) : (v->value == i);
        if (same != 0) {
            const char *tn = (d->name != NULL) ? d->name : "";
            if (json != 0) {
                sim_buf t;
                sim_buf_init(&t);
                sim_puts(&t, tn);
                sim_putc(&t, '#');
                sim_puts(&t, v->name);
                sim_json_string(out, t.p, t.len);
                sim_buf_free(&t);
            } else {
                sim_puts(out, tn);
                sim_putc(out, '#');
                sim_puts(out, v->name);
            }
            return;
        }
    }
    if (is_unsigned != 0) {
        sim_put_u64(out, u);
    } else {
        sim_put_i64(out, i);
    }
}

static void emit_type(sim_buf *out, int json, const unsigned char *p, uint32_t t, unsigned depth)
{
    const stc_type *d = sim_type(t);
    if ((depth > SIM_MAX_DEPTH) || (d == NULL) || (p == NULL)) {
        emit_unreadable(out, json);
        return;
    }
    switch (d->kind) {
    case STC_TK_SCALAR:
    case STC_TK_SUBRANGE:
        emit_scalar(out, json, (int)d->elem, p);
        break;
    case STC_TK_STRING:
        emit_string(out, json, d, p);
        break;
    case STC_TK_ENUM:
        emit_enum(out, json, p, d);
        break;
    case STC_TK_ARRAY:
        emit_array(out, json, p, d->elem_type, d->dims, d->count, d->stride, depth + 1U);
        break;
    case STC_TK_STRUCT:
    case STC_TK_INSTANCE:
        emit_record(out, json, p, d, depth);
        break;
    default:
        emit_unreadable(out, json);
        break;
    }
}

void sim_emit_value(sim_buf *out, int json, const unsigned char *addr, const sim_view *v)
{
    if (addr == NULL) {
        emit_unreadable(out, json);
    } else if (v->slice != 0) {
        emit_array(out, json, addr, v->type, v->dims, v->ndims, v->stride, 0U);
    } else {
        emit_type(out, json, addr, v->type, 0U);
    }
}

/* ---- reading values from text ------------------------------------------- */

void sim_value_free(sim_value *v)
{
    free(v->s);
    free(v->w);
    v->s = NULL;
    v->w = NULL;
}

static void value_init(sim_value *v)
{
    (void)memset(v, 0, sizeof *v);
    v->s = NULL;
    v->w = NULL;
}

/* Stores an integer in the memory representation of `elem` (its low
   bytes, as the VM's write_scalar does). */
static void store_int(sim_value *v, int elem, int64_t x)
{
    uint64_t u = (uint64_t)x;
    size_t size = sim_elem_size(elem);
    v->size = size;
    if (elem == STC_E_BOOL) {
        v->scalar.b[0] = (x != 0) ? 1U : 0U;
    } else if (size == 1U) {
        uint8_t t = (uint8_t)(u & 0xFFU);
        (void)memcpy(v->scalar.b, &t, sizeof t);
    } else if (size == 2U) {
        uint16_t t = (uint16_t)(u & 0xFFFFU);
        (void)memcpy(v->scalar.b, &t, sizeof t);
    } else if (size == 4U) {
        uint32_t t = (uint32_t)(u & 0xFFFFFFFFU);
        (void)memcpy(v->scalar.b, &t, sizeof t);
    } else {
        (void)memcpy(v->scalar.b, &u, sizeof u);
    }
}

static void put_slice(sim_buf *b, const char *s, size_t n)
{
    sim_put(b, s, n);
}

static int is_hex(char c)
{
    return ((c >= '0') && (c <= '9')) || ((c >= 'a') && (c <= 'f')) || ((c >= 'A') && (c <= 'F'));
}

static uint32_t hex_value(char c)
{
    if ((c >= '0') && (c <= '9')) {
        return (uint32_t)(c - '0');
    }
    if ((c >= 'a') && (c <= 'f')) {
        return (uint32_t)(c - 'a') + 10U;
    }
    return (uint32_t)(c - 'A') + 10U;
}

static int is_boundary(const char *s, size_t n, size_t i)
{
    return (i >= n) || ((((unsigned char)s[i]) & 0xC0U) != 0x80U);
}

/* stc_syntax's decode_string: the code points of a quoted literal, or its
   first problem in `msg`. */
static int decode_string(const char *text, size_t n, int wide, uint32_t **cps, size_t *count, sim_buf *msg)
{
    size_t inner_end = n;
    size_t i = 1U;
    size_t k = 0U;
    uint32_t *out = (uint32_t *)sim_alloc((n + 1U) * sizeof(uint32_t));
    if ((n >= 2U) && (text[n - 1U] == text[0])) {
        inner_end = n - 1U;
    }
    while (i < inner_end) {
        uint32_t c;
        size_t len = sim_utf8_next(&text[i], n - i, &c);
        char e;
        uint32_t simple = 0U;
        int has_simple = 1;
        size_t nd;
        size_t hex_end;
        if (c != (uint32_t)'$') {
            out[k] = c;
            k++;
            i += len;
            continue;
        }
        e = ((i + 1U) < n) ? text[i + 1U] : '\0';
        switch (e) {
        case '$':
            simple = (uint32_t)'$';
            break;
        case '\'':
            simple = (uint32_t)'\'';
            break;
        case '"':
            simple = (uint32_t)'"';
            break;
        case 'L':
        case 'l':
        case 'N':
        case 'n':
            simple = (uint32_t)'\n';
            break;
        case 'P':
        case 'p':
            simple = 0x0CU;
            break;
        case 'R':
        case 'r':
            simple = (uint32_t)'\r';
            break;
        case 'T':
        case 't':
            simple = (uint32_t)'\t';
            break;
        default:
            has_simple = 0;
            break;
        }
        if (has_simple != 0) {
            out[k] = simple;
            k++;
            i += 2U;
            continue;
        }
        nd = (wide != 0) ? 4U : 2U;
        hex_end = ((i + 1U + nd) < inner_end) ? (i + 1U + nd) : inner_end;
        if (((hex_end - (i + 1U)) == nd) && (is_boundary(text, n, hex_end) != 0)) {
            size_t j;
            int ok = 1;
            uint32_t v = 0U;
            for (j = i + 1U; j < hex_end; j++) {
                if (is_hex(text[j]) == 0) {
                    ok = 0;
                } else {
                    v = (v * 16U) + hex_value(text[j]);
                }
            }
            if (ok != 0) {
                if (wide == 0) {
                    out[k] = sim_cp1252_decode((uint8_t)v);
                } else if ((v >= 0xD800U) && (v <= 0xDFFFU)) {
                    sim_puts(msg, "`$");
                    put_slice(msg, &text[i + 1U], nd);
                    sim_puts(msg, "` is not a character");
                    free(out);
                    return 0;
                } else {
                    out[k] = v;
                }
                k++;
                i += 1U + nd;
                continue;
            }
        }
        {
            uint32_t sc;
            size_t slen = ((i + 1U) < inner_end) ? sim_utf8_next(&text[i + 1U], inner_end - (i + 1U), &sc) : 0U;
            sim_puts(msg, "invalid escape `$");
            put_slice(msg, &text[i + 1U], slen);
            sim_puts(msg, "`: use $$, $', $\", $L, $N, $P, $R, $T or $ and ");
            sim_puts(msg, (wide != 0) ? "four" : "two");
            sim_puts(msg, " hex digits");
            free(out);
            return 0;
        }
    }
    *cps = out;
    *count = k;
    return 1;
}

/* value.rs parse_string: a string literal (`'text'`, `"text"`, with `$`
   escapes, optionally STRING# / WSTRING#), or the bare text. */
static int parse_string(int wide, const char *t, size_t tn, sim_value *out, sim_buf *err)
{
    const char *body = t;
    size_t bn = tn;
    uint32_t *cps = NULL;
    size_t count = 0U;
    size_t i;
    const char *hash = (const char *)memchr(t, '#', tn);
    if (hash != NULL) {
        size_t pn = (size_t)(hash - t);
        const char *rest = &hash[1];
        size_t rn = tn - pn - 1U;
        if ((sim_ieq_z(t, pn, (wide != 0) ? "WSTRING" : "STRING") != 0) && (rn > 0U) &&
            ((rest[0] == '\'') || (rest[0] == '"'))) {
            body = rest;
            bn = rn;
        }
    }
    if ((bn > 0U) && ((body[0] == '\'') || (body[0] == '"'))) {
        char q = body[0];
        sim_buf msg;
        if ((bn < 2U) || (body[bn - 1U] != q)) {
            sim_puts(err, "the string `");
            sim_put(err, t, tn);
            sim_puts(err, "` has no closing ");
            sim_putc(err, q);
            return 0;
        }
        sim_buf_init(&msg);
        if (decode_string(body, bn, wide, &cps, &count, &msg) == 0) {
            sim_puts(err, "in the string `");
            sim_put(err, t, tn);
            sim_puts(err, "`: ");
            sim_put(err, msg.p, msg.len);
            sim_buf_free(&msg);
            return 0;
        }
        sim_buf_free(&msg);
    } else {
        size_t j = 0U;
        cps = (uint32_t *)sim_alloc((bn + 1U) * sizeof(uint32_t));
        while (j < bn) {
            j += sim_utf8_next(&body[j], bn - j, &cps[count]);
            count++;
        }
    }
    out->is_string = 1;
    out->wide = wide;
    if (wide != 0) {
        size_t k = 0U;
        out->w = (uint16_t *)sim_alloc(((2U * count) + 1U) * sizeof(uint16_t));
        for (i = 0U; i < count; i++) {
            uint32_t c = cps[i];
            if (c >= 0x10000U) {
                c -= 0x10000U;
                out->w[k] = (uint16_t)(0xD800U + (c >> 10));
                out->w[k + 1U] = (uint16_t)(0xDC00U + (c & 0x3FFU));
                k += 2U;
            } else {
                out->w[k] = (uint16_t)c;
                k++;
            }
        }
        out->len = k;
    } else {
        out->s = (uint8_t *)sim_alloc(count + 1U);
        for (i = 0U; i < count; i++) {
            int b = sim_cp1252_encode(cps[i]);
            if (b < 0) {
                free(cps);
                sim_value_free(out);
                out->is_string = 0;
                sim_putc(err, '`');
                sim_put(err, t, tn);
                sim_puts(err, "` has characters a STRING cannot hold (use a WSTRING)");
                return 0;
            }
            out->s[i] = (uint8_t)b;
        }
        out->len = count;
    }
    free(cps);
    return 1;
}

static int parse_scalar(int elem, const char *t, size_t tn, sim_value *out, sim_buf *err)
{
    int quoted = (tn >= 2U) && ((t[0] == '\'') || (t[0] == '"'));
    if (((elem == STC_E_CHAR) || (elem == STC_E_WCHAR)) && (quoted != 0)) {
        sim_value s;
        int64_t code = 0;
        value_init(&s);
        if (parse_string((elem == STC_E_WCHAR) ? 1 : 0, t, tn, &s, err) == 0) {
            return 0;
        }
        if ((elem == STC_E_WCHAR) && (s.len > 0U)) {
            code = (int64_t)s.w[0];
        } else if ((elem == STC_E_CHAR) && (s.len > 0U)) {
            code = (int64_t)s.s[0];
        } else {
            code = 0;
        }
        sim_value_free(&s);
        store_int(out, elem, code);
        return 1;
    }
    if ((elem == STC_E_STRING) || (elem == STC_E_WSTRING) || (elem < 0) ||
        (stc_parse_value((uint8_t)elem, t, tn, out->scalar.b, 0U) != 0U)) {
        sim_putc(err, '`');
        sim_put(err, t, tn);
        sim_puts(err, "` cannot be read as ");
        sim_puts(err, sim_elem_name(elem));
        sim_puts(err, " (expected an ST literal within the type's range)");
        return 0;
    }
    out->size = sim_elem_size(elem);
    return 1;
}

static int parse_enum(const stc_type *d, const char *t, size_t tn, sim_value *out, sim_buf *err)
{
    const char *name = (d->name != NULL) ? d->name : "";
    const char *vn = t;
    size_t vl = tn;
    const char *hash = (const char *)memchr(t, '#', tn);
    uint32_t k;
    if (hash != NULL) {
        size_t pn = (size_t)(hash - t);
        if (sim_ieq_z(t, pn, name) == 0) {
            sim_putc(err, '`');
            sim_put(err, t, tn);
            sim_puts(err, "` is a value of `");
            sim_put(err, t, pn);
            sim_puts(err, "`, not of the enumerated type ");
            sim_puts(err, name);
            return 0;
        }
        vn = &hash[1];
        vl = tn - pn - 1U;
    }
    sim_trim(&vn, &vl);
    for (k = 0U; k < d->count; k++) {
        if (sim_ieq_z(vn, vl, d->values[k].name) != 0) {
            store_int(out, (int)d->elem, d->values[k].value);
            return 1;
        }
    }
    sim_putc(err, '`');
    sim_put(err, t, tn);
    sim_puts(err, "` is not a value of ");
    sim_puts(err, name);
    sim_puts(err, " (its values: ");
    for (k = 0U; k < d->count; k++) {
        if (k > 0U) {
            sim_puts(err, ", ");
        }
        sim_puts(err, d->values[k].name);
    }
    sim_putc(err, ')');
    return 0;
}

int sim_parse_for(const sim_view *v, const char *text, size_t n, sim_value *out, sim_buf *err)
{
    const char *t = text;
    size_t tn = n;
    const stc_type *d = (v->slice != 0) ? NULL : sim_type(v->type);
    value_init(out);
    sim_trim(&t, &tn);
    if ((d != NULL) && (d->kind == (uint8_t)STC_TK_SCALAR)) {
        return parse_scalar((int)d->elem, t, tn, out, err);
    }
    if ((d != NULL) && (d->kind == (uint8_t)STC_TK_SUBRANGE)) {
        int64_t i;
        uint64_t u;
        int is_unsigned;
        int outside;
        if (parse_scalar((int)d->elem, t, tn, out, err) == 0) {
            return 0;
        }
        if (sim_read_int((int)d->elem, out->scalar.b, &i, &u, &is_unsigned) != 0) {
            if (is_unsigned != 0) {
                outside = ((d->lo > 0) && (u < (uint64_t)d->lo)) || (d->hi < 0) || (u > (uint64_t)d->hi);
            } else {
                outside = (i < d->lo) || (i > d->hi);
            }
            if (outside != 0) {
                sim_putc(err, '`');
                sim_put(err, t, tn);
                sim_puts(err, "` is outside the subrange ");
                sim_put_i64(err, d->lo);
                sim_puts(err, "..");
                sim_put_i64(err, d->hi);
                sim_puts(err, " of this variable");
                return 0;
            }
        }
        return 1;
    }
    if ((d != NULL) && (d->kind == (uint8_t)STC_TK_STRING)) {
        return parse_string((d->wide != 0U) ? 1 : 0, t, tn, out, err);
    }
    if ((d != NULL) && (d->kind == (uint8_t)STC_TK_ENUM)) {
        return parse_enum(d, t, tn, out, err);
    }
    sim_puts(err, "cannot assign `");
    sim_put(err, t, tn);
    sim_puts(err, "` to ");
    if (v->slice != 0) {
        sim_puts(err, "part of an ARRAY");
    } else {
        sim_puts(err, "a whole ");
        sim_describe(err, v->type);
    }
    sim_puts(err, ": only elementary, string and enumerated variables take a value (name an element or a member)");
    return 0;
}

int sim_write_value(unsigned char *addr, const sim_view *v, const sim_value *val)
{
    const stc_type *d;
    int elem;
    if ((addr == NULL) || (v->slice != 0)) {
        return 0;
    }
    elem = sim_scalar_of(v->type);
    if (elem >= 0) {
        size_t size = sim_elem_size(elem);
        if ((val->is_string != 0) || (size == 0U) || (val->size != size)) {
            return 0;
        }
        (void)memcpy(addr, val->scalar.b, size);
        return 1;
    }
    d = sim_type(v->type);
    if ((d != NULL) && (d->kind == (uint8_t)STC_TK_STRING) && (val->is_string != 0) &&
        ((d->wide != 0U) == (val->wide != 0))) {
        size_t n = (val->len < (size_t)d->cap) ? val->len : (size_t)d->cap;
        uint16_t len16 = (uint16_t)(n & 0xFFFFU);
        (void)memcpy(addr, &len16, sizeof len16);
        if (d->wide != 0U) {
            if (n > 0U) {
                (void)memcpy(&addr[2], val->w, n * sizeof(uint16_t));
            }
        } else {
            if (n > 0U) {
                (void)memcpy(&addr[2], val->s, n);
            }
        }
        return 1;
    }
    return 0;
}

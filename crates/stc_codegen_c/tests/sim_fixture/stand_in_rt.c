/*
 * stand_in_rt.c - test-only stand-ins for the parts of stc_rt.c the
 * simulation harness needs (faults, the clock, the watchdog,
 * stc_parse_value and stc_convert_scalar), used until the real stc_rt.c
 * provides them. Not shipped. stc_parse_value follows stc_values's
 * parse_value closely enough for the harness tests (a duration fraction
 * keeps at most 18 digits).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stc_meta.h"
#include "stc_rt.h"

uint32_t stc_convert_scalar(uint8_t from_elem, const void *src, uint8_t to_elem, void *dst);
uint32_t stc_parse_value(uint8_t elem, const char *text, size_t len, void *dst, uint32_t cap);

uint32_t stc_fault_kind;
uint32_t stc_fault_site;
int64_t stc_clock;
uint64_t stc_steps;

void stc_fault(uint32_t kind, uint32_t site)
{
    if (stc_fault_kind == 0U) {
        stc_fault_kind = kind;
        stc_fault_site = site;
    }
}

const char *stc_fault_text(uint32_t kind)
{
    switch (kind) {
    case STC_FAULT_DIVISION_BY_ZERO:
        return "division by zero";
    case STC_FAULT_INDEX:
        return "array index out of bounds";
    case STC_FAULT_SUBRANGE:
        return "subrange violation";
    case STC_FAULT_CONVERSION:
        return "conversion failure";
    case STC_FAULT_MUX:
        return "MUX selector out of range";
    case STC_FAULT_FOR_STEP_ZERO:
        return "FOR step of zero";
    case STC_FAULT_WATCHDOG:
        return "watchdog";
    default:
        return "unknown fault";
    }
}

/* ---- integers ---------------------------------------------------------- */

typedef struct {
    int neg;
    uint64_t mag;
} big;

static int is_signed(int e)
{
    return (e == STC_E_SINT) || (e == STC_E_INT) || (e == STC_E_DINT) || (e == STC_E_LINT);
}

static int is_unsigned_int(int e)
{
    return (e == STC_E_USINT) || (e == STC_E_UINT) || (e == STC_E_UDINT) || (e == STC_E_ULINT) ||
           (e == STC_E_BYTE) || (e == STC_E_WORD) || (e == STC_E_DWORD) || (e == STC_E_LWORD);
}

static int width(int e)
{
    switch (e) {
    case STC_E_SINT:
    case STC_E_USINT:
    case STC_E_BYTE:
        return 8;
    case STC_E_INT:
    case STC_E_UINT:
    case STC_E_WORD:
        return 16;
    case STC_E_DINT:
    case STC_E_UDINT:
    case STC_E_DWORD:
        return 32;
    default:
        return 64;
    }
}

static int in_range(int e, big v)
{
    int w = width(e);
    if (is_signed(e)) {
        uint64_t lim = (uint64_t)1 << (w - 1);
        return v.neg ? (v.mag <= lim) : (v.mag < lim);
    }
    if (v.neg && (v.mag != 0U)) {
        return 0;
    }
    return (w == 64) || (v.mag < ((uint64_t)1 << w));
}

static void store(int e, big v, void *dst)
{
    uint64_t u = v.neg ? ((uint64_t)0 - v.mag) : v.mag;
    switch (width(e)) {
    case 8: {
        uint8_t t = (uint8_t)(u & 0xFFU);
        memcpy(dst, &t, 1);
        break;
    }
    case 16: {
        uint16_t t = (uint16_t)(u & 0xFFFFU);
        memcpy(dst, &t, 2);
        break;
    }
    case 32: {
        uint32_t t = (uint32_t)(u & 0xFFFFFFFFU);
        memcpy(dst, &t, 4);
        break;
    }
    default:
        memcpy(dst, &u, 8);
        break;
    }
}

static int load(int e, const void *src, big *v)
{
    v->neg = 0;
    if (e == STC_E_BOOL) {
        uint8_t b;
        memcpy(&b, src, 1);
        v->mag = (b != 0U) ? 1U : 0U;
        return 1;
    }
    if (is_signed(e)) {
        int64_t x;
        switch (width(e)) {
        case 8: {
            int8_t t;
            memcpy(&t, src, 1);
            x = t;
            break;
        }
        case 16: {
            int16_t t;
            memcpy(&t, src, 2);
            x = t;
            break;
        }
        case 32: {
            int32_t t;
            memcpy(&t, src, 4);
            x = t;
            break;
        }
        default:
            memcpy(&x, src, 8);
            break;
        }
        v->neg = x < 0;
        v->mag = (x < 0) ? ((uint64_t)0 - (uint64_t)x) : (uint64_t)x;
        return 1;
    }
    if (is_unsigned_int(e)) {
        switch (width(e)) {
        case 8: {
            uint8_t t;
            memcpy(&t, src, 1);
            v->mag = t;
            break;
        }
        case 16: {
            uint16_t t;
            memcpy(&t, src, 2);
            v->mag = t;
            break;
        }
        case 32: {
            uint32_t t;
            memcpy(&t, src, 4);
            v->mag = t;
            break;
        }
        default:
            memcpy(&v->mag, src, 8);
            break;
        }
        return 1;
    }
    return 0;
}

/* Integers wrap (stc_values::convert); REAL/LREAL to an integer rounds
   ties to even and faults outside the range. */
uint32_t stc_convert_scalar(uint8_t from_elem, const void *src, uint8_t to_elem, void *dst)
{
    big v;
    int to_int = is_signed(to_elem) || is_unsigned_int(to_elem);
    if (load(from_elem, src, &v) && to_int) {
        store(to_elem, v, dst);
        return 0U;
    }
    if (load(from_elem, src, &v) && ((to_elem == STC_E_REAL) || (to_elem == STC_E_LREAL))) {
        double d = v.neg ? -(double)v.mag : (double)v.mag;
        if (to_elem == STC_E_REAL) {
            float f = (float)d;
            memcpy(dst, &f, 4);
        } else {
            memcpy(dst, &d, 8);
        }
        return 0U;
    }
    if ((from_elem == STC_E_REAL) || (from_elem == STC_E_LREAL)) {
        double d;
        if (from_elem == STC_E_REAL) {
            float f;
            memcpy(&f, src, 4);
            d = (double)f;
        } else {
            memcpy(&d, src, 8);
        }
        if (to_int) {
            double r = nearbyint(d);
            if (!isfinite(r) || (r >= 18446744073709551616.0) || (r < -9223372036854775808.0)) {
                return STC_FAULT_CONVERSION;
            }
            v.neg = r < 0.0;
            v.mag = v.neg ? (uint64_t)(-r) : (uint64_t)r;
            if (!in_range(to_elem, v)) {
                return STC_FAULT_CONVERSION;
            }
            store(to_elem, v, dst);
            return 0U;
        }
        if (to_elem == STC_E_REAL) {
            float f = (float)d;
            memcpy(dst, &f, 4);
            return 0U;
        }
        if (to_elem == STC_E_LREAL) {
            memcpy(dst, &d, 8);
            return 0U;
        }
    }
    return STC_FAULT_CONVERSION;
}

/* ---- parse_value ---------------------------------------------------------- */

static int upper(int c)
{
    return ((c >= 'a') && (c <= 'z')) ? (c - 'a' + 'A') : c;
}

static int ieq(const char *a, size_t n, const char *z)
{
    size_t i;
    if (strlen(z) != n) {
        return 0;
    }
    for (i = 0; i < n; i++) {
        if (upper((unsigned char)a[i]) != upper((unsigned char)z[i])) {
            return 0;
        }
    }
    return 1;
}

static const char *const elem_names[] = {
    "BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT", "REAL", "LREAL",
    "TIME", "LTIME", "DATE", "LDATE", "TOD", "LTOD", "DT", "LDT", "STRING", "WSTRING", "CHAR",
    "WCHAR", "BYTE", "WORD", "DWORD", "LWORD"
};

static int elem_from_name(const char *s, size_t n)
{
    int i;
    for (i = 0; i < 27; i++) {
        if (ieq(s, n, elem_names[i])) {
            return i;
        }
    }
    if (ieq(s, n, "TIME_OF_DAY")) {
        return STC_E_TOD;
    }
    if (ieq(s, n, "LTIME_OF_DAY")) {
        return STC_E_LTOD;
    }
    if (ieq(s, n, "DATE_AND_TIME")) {
        return STC_E_DT;
    }
    if (ieq(s, n, "LDATE_AND_TIME")) {
        return STC_E_LDT;
    }
    return -1;
}

static int digit_of(int c, unsigned base, unsigned *d)
{
    unsigned v;
    if ((c >= '0') && (c <= '9')) {
        v = (unsigned)(c - '0');
    } else if ((c >= 'a') && (c <= 'z')) {
        v = (unsigned)(c - 'a') + 10U;
    } else if ((c >= 'A') && (c <= 'Z')) {
        v = (unsigned)(c - 'A') + 10U;
    } else {
        return 0;
    }
    if (v >= base) {
        return 0;
    }
    *d = v;
    return 1;
}

static int digits_value(const char *s, size_t n, unsigned base, uint64_t *out)
{
    uint64_t v = 0;
    int over = 0;
    size_t i;
    if (n == 0) {
        return 0;
    }
    if ((s[0] == '_') || (s[n - 1] == '_')) {
        return 0;
    }
    for (i = 0; i + 1 < n; i++) {
        if ((s[i] == '_') && (s[i + 1] == '_')) {
            return 0;
        }
    }
    for (i = 0; i < n; i++) {
        unsigned d;
        if (s[i] == '_') {
            continue;
        }
        if (!digit_of((unsigned char)s[i], base, &d)) {
            return 0;
        }
        if (v > (UINT64_MAX - d) / base) {
            over = 1;
        } else {
            v = v * base + d;
        }
    }
    if (over) {
        return 0;
    }
    *out = v;
    return 1;
}

static int parse_int(const char *s, size_t n, uint64_t *out)
{
    size_t i;
    for (i = 0; i < n; i++) {
        if (!((s[i] >= '0' && s[i] <= '9') || s[i] == '_')) {
            return 0;
        }
    }
    return digits_value(s, n, 10, out);
}

static int parse_based(const char *s, size_t n, uint64_t *out)
{
    const char *h = memchr(s, '#', n);
    size_t i;
    uint64_t base = 0;
    size_t digits = 0;
    int seen = 0;
    if (h == NULL) {
        return 0;
    }
    for (i = 0; i < (size_t)(h - s); i++) {
        if (s[i] == '_') {
            continue;
        }
        if (!seen && s[i] == '+') {
            seen = 1;
            continue;
        }
        seen = 1;
        if (s[i] < '0' || s[i] > '9') {
            return 0;
        }
        if (base < 1000) {
            base = base * 10 + (uint64_t)(s[i] - '0');
        }
        digits++;
    }
    if (digits == 0 || (base != 2 && base != 8 && base != 16)) {
        return 0;
    }
    return digits_value(h + 1, n - (size_t)(h - s) - 1, (unsigned)base, out);
}

/* strip_type_prefix: `NAME#rest` must name `to`. */
static int strip_prefix(int to, const char **s, size_t *n)
{
    const char *h = memchr(*s, '#', *n);
    int c;
    if (h == NULL) {
        return 1;
    }
    c = (unsigned char)(*s)[0];
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'))) {
        return 1;
    }
    if (elem_from_name(*s, (size_t)(h - *s)) != to) {
        return 0;
    }
    *n -= (size_t)(h - *s) + 1;
    *s = h + 1;
    return 1;
}

static int digit_run(const char *s, size_t n)
{
    size_t i;
    if (n == 0 || s[0] < '0' || s[0] > '9' || s[n - 1] < '0' || s[n - 1] > '9') {
        return 0;
    }
    for (i = 0; i < n; i++) {
        if (!((s[i] >= '0' && s[i] <= '9') || s[i] == '_')) {
            return 0;
        }
        if (i + 1 < n && s[i] == '_' && s[i + 1] == '_') {
            return 0;
        }
    }
    return 1;
}

/* 128-bit (hi, lo) = a * b, then / d (d < 2^63). */
static uint64_t muldiv(uint64_t a, uint64_t b, uint64_t d)
{
    uint64_t a0 = a & 0xFFFFFFFFU, a1 = a >> 32, b0 = b & 0xFFFFFFFFU, b1 = b >> 32;
    uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    uint64_t mid = (p00 >> 32) + (p01 & 0xFFFFFFFFU) + (p10 & 0xFFFFFFFFU);
    uint64_t lo = (p00 & 0xFFFFFFFFU) | (mid << 32);
    uint64_t hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
    uint64_t q = 0, r = 0;
    int i;
    for (i = 127; i >= 0; i--) {
        uint64_t bit = (i >= 64) ? ((hi >> (i - 64)) & 1U) : ((lo >> i) & 1U);
        r = (r << 1) | bit;
        q <<= 1;
        if (r >= d) {
            r -= d;
            q |= 1U;
        }
    }
    return q;
}

#define NS_S 1000000000ULL
#define NS_D 86400000000000ULL

static int parse_duration(const char *t, size_t n, int64_t *out)
{
    static const char *const units[7] = { "D", "H", "M", "S", "MS", "US", "NS" };
    static const uint64_t size[7] = { 86400000000000ULL, 3600000000000ULL, 60000000000ULL, NS_S, 1000000ULL, 1000ULL, 1ULL };
    static const uint64_t limit[7] = { UINT64_MAX, 24, 60, 60, 1000, 1000, 1000 };
    const char *h = memchr(t, '#', n);
    const char *s = h ? h + 1 : t + n;
    size_t sn = (size_t)(t + n - s);
    int neg = 0;
    uint64_t total = 0;
    int last = -1;
    int frac_seen = 0;
    if (sn > 0 && (s[0] == '-' || s[0] == '+')) {
        neg = s[0] == '-';
        s++;
        sn--;
    }
    if (sn == 0) {
        return 0;
    }
    while (sn > 0) {
        size_t a = 0, b, i;
        int ui = -1;
        const char *dot;
        uint64_t iv, part;
        if (frac_seen) {
            return 0;
        }
        while (a < sn && ((s[a] >= '0' && s[a] <= '9') || s[a] == '_' || s[a] == '.')) {
            a++;
        }
        b = a;
        while (b < sn && ((s[b] >= 'a' && s[b] <= 'z') || (s[b] >= 'A' && s[b] <= 'Z'))) {
            b++;
        }
        if (a == 0) {
            return 0;
        }
        for (i = 0; i < 7; i++) {
            if (ieq(s + a, b - a, units[i])) {
                ui = (int)i;
            }
        }
        if (ui < 0 || (last >= 0 && ui <= last)) {
            return 0;
        }
        dot = memchr(s, '.', a);
        if (!digits_value(s, dot ? (size_t)(dot - s) : a, 10, &iv)) {
            return 0;
        }
        if (last >= 0 && iv >= limit[ui]) {
            return 0;
        }
        if (iv > (uint64_t)INT64_MAX / size[ui]) {
            return 0;
        }
        part = iv * size[ui];
        if (dot) {
            const char *f = dot + 1;
            size_t fn = a - (size_t)(dot - s) - 1, k;
            uint64_t fv = 0, scale = 1;
            frac_seen = 1;
            if (fn == 0) {
                return 0;
            }
            for (k = 0; k < fn; k++) {
                if (f[k] < '0' || f[k] > '9') {
                    return 0;
                }
                if (k < 18) {
                    fv = fv * 10 + (uint64_t)(f[k] - '0');
                    scale *= 10;
                }
            }
            part += muldiv(fv, size[ui], scale);
        }
        if (part > (uint64_t)INT64_MAX - total) {
            return 0;
        }
        total += part;
        last = ui;
        s += b;
        sn -= b;
        if (sn > 0 && s[0] == '_') {
            s++;
            sn--;
            if (sn == 0) {
                return 0;
            }
        }
    }
    *out = neg ? -(int64_t)total : (int64_t)total;
    return 1;
}

static int number(const char *s, size_t n, uint64_t *v)
{
    size_t i;
    if (n == 0) {
        return 0;
    }
    for (i = 0; i < n; i++) {
        if (!((s[i] >= '0' && s[i] <= '9') || s[i] == '_')) {
            return 0;
        }
    }
    return digits_value(s, n, 10, v);
}

static int64_t days_from_civil(int64_t y, int64_t m, int64_t d)
{
    int64_t yy = (m <= 2) ? y - 1 : y;
    int64_t era = (yy >= 0 ? yy : yy - 399) / 400;
    int64_t yoe = yy - era * 400;
    int64_t mp = (m + 9) % 12;
    int64_t doy = (153 * mp + 2) / 5 + d - 1;
    int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + doe - 719468;
}

static int parse_date_part(const char *s, size_t n, int64_t *days)
{
    const char *p1 = memchr(s, '-', n), *p2;
    uint64_t y, m, d, dim;
    if (!p1) {
        return 0;
    }
    p2 = memchr(p1 + 1, '-', (size_t)(s + n - p1 - 1));
    if (!p2) {
        return 0;
    }
    if (!number(s, (size_t)(p1 - s), &y) || !number(p1 + 1, (size_t)(p2 - p1 - 1), &m) ||
        !number(p2 + 1, (size_t)(s + n - p2 - 1), &d)) {
        return 0;
    }
    if (y > 9999 || m < 1 || m > 12) {
        return 0;
    }
    if (m == 4 || m == 6 || m == 9 || m == 11) {
        dim = 30;
    } else if (m == 2) {
        dim = ((y % 4 == 0 && y % 100 != 0) || y % 400 == 0) ? 29 : 28;
    } else {
        dim = 31;
    }
    if (d < 1 || d > dim) {
        return 0;
    }
    *days = days_from_civil((int64_t)y, (int64_t)m, (int64_t)d);
    return 1;
}

static int parse_tod_part(const char *s, size_t n, uint64_t *ns)
{
    const char *p1 = memchr(s, ':', n), *p2, *sec, *dot;
    uint64_t h, m, sc;
    size_t sn;
    if (!p1) {
        return 0;
    }
    p2 = memchr(p1 + 1, ':', (size_t)(s + n - p1 - 1));
    if (!p2) {
        return 0;
    }
    sec = p2 + 1;
    sn = (size_t)(s + n - sec);
    dot = memchr(sec, '.', sn);
    if (!number(s, (size_t)(p1 - s), &h) || !number(p1 + 1, (size_t)(p2 - p1 - 1), &m) ||
        !number(sec, dot ? (size_t)(dot - sec) : sn, &sc)) {
        return 0;
    }
    if (h > 23 || m > 59 || sc > 59) {
        return 0;
    }
    *ns = h * 3600 * NS_S + m * 60 * NS_S + sc * NS_S;
    if (dot) {
        const char *f = dot + 1;
        size_t fn = (size_t)(sec + sn - f), k;
        uint64_t fv = 0, scale = 1;
        if (fn == 0) {
            return 0;
        }
        for (k = 0; k < fn; k++) {
            if (f[k] < '0' || f[k] > '9') {
                return 0;
            }
            if (k < 9) {
                fv = fv * 10 + (uint64_t)(f[k] - '0');
                scale *= 10;
            }
        }
        *ns += fv * NS_S / scale;
    }
    return 1;
}

static int time_prefix_kind(const char *p, size_t n)
{
    if (ieq(p, n, "T") || ieq(p, n, "TIME") || ieq(p, n, "LT") || ieq(p, n, "LTIME")) {
        return 1;
    }
    if (ieq(p, n, "D") || ieq(p, n, "DATE") || ieq(p, n, "LD") || ieq(p, n, "LDATE")) {
        return 2;
    }
    if (ieq(p, n, "TOD") || ieq(p, n, "TIME_OF_DAY") || ieq(p, n, "LTOD") || ieq(p, n, "LTIME_OF_DAY")) {
        return 3;
    }
    if (ieq(p, n, "DT") || ieq(p, n, "DATE_AND_TIME") || ieq(p, n, "LDT") || ieq(p, n, "LDATE_AND_TIME")) {
        return 4;
    }
    return 0;
}

static int utf8_first(const char *s, size_t n, uint32_t *cp)
{
    const unsigned char *u = (const unsigned char *)s;
    if (n == 0) {
        *cp = 0;
        return 1;
    }
    if (u[0] < 0x80) {
        *cp = u[0];
    } else if ((u[0] & 0xE0) == 0xC0 && n >= 2) {
        *cp = ((uint32_t)(u[0] & 0x1F) << 6) | (u[1] & 0x3F);
    } else if ((u[0] & 0xF0) == 0xE0 && n >= 3) {
        *cp = ((uint32_t)(u[0] & 0x0F) << 12) | ((uint32_t)(u[1] & 0x3F) << 6) | (u[2] & 0x3F);
    } else if (n >= 4) {
        *cp = ((uint32_t)(u[0] & 0x07) << 18) | ((uint32_t)(u[1] & 0x3F) << 12) | ((uint32_t)(u[2] & 0x3F) << 6) |
              (u[3] & 0x3F);
    } else {
        return 0;
    }
    return 1;
}

static const uint16_t high1252[32] = {
    0x20AC, 0x0081, 0x201A, 0x0192, 0x201E, 0x2026, 0x2020, 0x2021, 0x02C6, 0x2030, 0x0160,
    0x2039, 0x0152, 0x008D, 0x017D, 0x008F, 0x0090, 0x2018, 0x2019, 0x201C, 0x201D, 0x2022,
    0x2013, 0x2014, 0x02DC, 0x2122, 0x0161, 0x203A, 0x0153, 0x009D, 0x017E, 0x0178
};

uint32_t stc_parse_value(uint8_t elem, const char *text, size_t len, void *dst, uint32_t cap)
{
    const char *s = text;
    size_t n = len;
    (void)cap;
    if (elem == STC_E_CHAR || elem == STC_E_WCHAR) {
        uint32_t cp;
        if (!utf8_first(text, len, &cp)) {
            return STC_FAULT_CONVERSION;
        }
        if (elem == STC_E_CHAR) {
            uint8_t b;
            int i, found = -1;
            if (cp <= 0x7F || (cp >= 0xA0 && cp <= 0xFF)) {
                found = (int)cp;
            }
            for (i = 0; i < 32 && found < 0; i++) {
                if (high1252[i] == cp) {
                    found = 0x80 + i;
                }
            }
            if (found < 0) {
                return STC_FAULT_CONVERSION;
            }
            b = (uint8_t)found;
            memcpy(dst, &b, 1);
        } else {
            uint16_t w;
            if (cp > 0xFFFF) {
                return STC_FAULT_CONVERSION;
            }
            w = (uint16_t)cp;
            memcpy(dst, &w, 2);
        }
        return 0U;
    }
    if (elem == STC_E_STRING || elem == STC_E_WSTRING) {
        return STC_FAULT_CONVERSION; /* not needed by the harness */
    }
    while (n > 0 && (s[0] == ' ' || s[0] == '\t' || s[0] == '\r' || s[0] == '\n')) {
        s++;
        n--;
    }
    while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r' || s[n - 1] == '\n')) {
        n--;
    }
    if (n == 0) {
        return STC_FAULT_CONVERSION;
    }
    if (elem == STC_E_BOOL) {
        uint8_t b;
        if (!strip_prefix(STC_E_BOOL, &s, &n)) {
            return STC_FAULT_CONVERSION;
        }
        if (ieq(s, n, "TRUE") || (n == 1 && s[0] == '1')) {
            b = 1;
        } else if (ieq(s, n, "FALSE") || (n == 1 && s[0] == '0')) {
            b = 0;
        } else {
            return STC_FAULT_CONVERSION;
        }
        memcpy(dst, &b, 1);
        return 0U;
    }
    if (is_signed(elem) || is_unsigned_int(elem)) {
        big v;
        if (!strip_prefix(elem, &s, &n)) {
            return STC_FAULT_CONVERSION;
        }
        v.neg = 0;
        if (n > 0 && (s[0] == '-' || s[0] == '+')) {
            v.neg = s[0] == '-';
            s++;
            n--;
        }
        if (memchr(s, '#', n) ? !parse_based(s, n, &v.mag) : !parse_int(s, n, &v.mag)) {
            return STC_FAULT_CONVERSION;
        }
        if (!in_range(elem, v)) {
            return STC_FAULT_CONVERSION;
        }
        store(elem, v, dst);
        return 0U;
    }
    if (elem == STC_E_REAL || elem == STC_E_LREAL) {
        const char *u;
        size_t un, i;
        int neg = 0;
        char buf[128];
        size_t k = 0;
        const char *e, *dot, *mant_end;
        double x;
        if (!strip_prefix(elem, &s, &n)) {
            return STC_FAULT_CONVERSION;
        }
        u = s;
        un = n;
        if (un > 0 && (u[0] == '-' || u[0] == '+')) {
            neg = u[0] == '-';
            u++;
            un--;
        }
        if (ieq(u, un, "INF") || (ieq(u, un, "NAN") && un == n)) {
            if (ieq(u, un, "INF")) {
                x = neg ? -HUGE_VAL : HUGE_VAL;
            } else {
                x = nan("");
            }
        } else {
            e = NULL;
            for (i = 0; i < un; i++) {
                if (u[i] == 'e' || u[i] == 'E') {
                    e = u + i;
                    break;
                }
            }
            mant_end = e ? e : u + un;
            dot = memchr(u, '.', (size_t)(mant_end - u));
            if (!digit_run(u, dot ? (size_t)(dot - u) : (size_t)(mant_end - u))) {
                return STC_FAULT_CONVERSION;
            }
            if (dot && !digit_run(dot + 1, (size_t)(mant_end - dot - 1))) {
                return STC_FAULT_CONVERSION;
            }
            if (e) {
                const char *es = e + 1;
                size_t en = (size_t)(u + un - es);
                if (en > 0 && (es[0] == '-' || es[0] == '+')) {
                    es++;
                    en--;
                }
                if (!digit_run(es, en)) {
                    return STC_FAULT_CONVERSION;
                }
            }
            for (i = 0; i < n && k + 1 < sizeof buf; i++) {
                if (s[i] != '_') {
                    buf[k++] = s[i];
                }
            }
            buf[k] = 0;
            if (elem == STC_E_REAL) {
                x = (double)strtof(buf, NULL);
            } else {
                x = strtod(buf, NULL);
            }
            if (!isfinite(x)) {
                return STC_FAULT_CONVERSION;
            }
        }
        if (elem == STC_E_REAL) {
            float f = (float)x;
            memcpy(dst, &f, 4);
        } else {
            memcpy(dst, &x, 8);
        }
        return 0U;
    }
    {
        /* time and date types: with or without their prefix */
        int kind = (elem == STC_E_TIME || elem == STC_E_LTIME) ? 1
                   : (elem == STC_E_DATE || elem == STC_E_LDATE) ? 2
                   : (elem == STC_E_TOD || elem == STC_E_LTOD) ? 3
                   : (elem == STC_E_DT || elem == STC_E_LDT) ? 4 : 0;
        const char *h = memchr(s, '#', n);
        const char *body = h ? h + 1 : s;
        size_t bn = h ? n - (size_t)(h - s) - 1 : n;
        int64_t v;
        if (kind == 0) {
            return STC_FAULT_CONVERSION;
        }
        if (h && time_prefix_kind(s, (size_t)(h - s)) != kind) {
            return STC_FAULT_CONVERSION;
        }
        if (kind == 1) {
            char buf[256];
            if (n + 3 > sizeof buf) {
                return STC_FAULT_CONVERSION;
            }
            if (!h) {
                buf[0] = 'T';
                buf[1] = '#';
                memcpy(buf + 2, s, n);
                if (!parse_duration(buf, n + 2, &v)) {
                    return STC_FAULT_CONVERSION;
                }
            } else if (!parse_duration(s, n, &v)) {
                return STC_FAULT_CONVERSION;
            }
        } else if (kind == 2) {
            int64_t days;
            if (!parse_date_part(body, bn, &days)) {
                return STC_FAULT_CONVERSION;
            }
            v = days * 86400;
        } else if (kind == 3) {
            uint64_t ns;
            if (!parse_tod_part(body, bn, &ns)) {
                return STC_FAULT_CONVERSION;
            }
            v = (int64_t)ns;
        } else {
            const char *p = body;
            int dashes = 0;
            size_t i, split = 0;
            int64_t days;
            uint64_t ns;
            for (i = 0; i < bn; i++) {
                if (p[i] == '-') {
                    dashes++;
                    if (dashes == 3) {
                        split = i;
                        break;
                    }
                }
            }
            if (dashes < 3 || !parse_date_part(p, split, &days) || !parse_tod_part(p + split + 1, bn - split - 1, &ns)) {
                return STC_FAULT_CONVERSION;
            }
            if (days > 106751 || days < -106752) {
                return STC_FAULT_CONVERSION;
            }
            if (days == -106752) {
                /* the first day that fits only partly */
                uint64_t off = 106752ULL * NS_D - ((uint64_t)INT64_MAX + 1U);
                if (ns < off) {
                    return STC_FAULT_CONVERSION;
                }
                v = INT64_MIN + (int64_t)(ns - off);
            } else {
                v = days * (int64_t)NS_D;
                if (days == 106751 && ns > (uint64_t)INT64_MAX - 106751ULL * NS_D) {
                    return STC_FAULT_CONVERSION;
                }
                v += (int64_t)ns;
            }
        }
        memcpy(dst, &v, 8);
        return 0U;
    }
}

/*
 * stc_sim_text.c - buffers, UTF-8, and the value formats of `stc run`
 * reports: durations, dates, REAL numbers (the shortest round-trip digits,
 * laid out as docs/semantics-notes.md, "Text of REAL and LREAL values",
 * specifies and stc_syntax::real implements), JSON and ST strings.
 */
#include "stc_sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- memory ------------------------------------------------------------ */

static void out_of_memory(void)
{
    (void)fputs("error: out of memory\n", stderr);
    exit(2);
}

void *sim_alloc(size_t n)
{
    void *p = malloc((n == 0U) ? 1U : n);
    if (p == NULL) {
        out_of_memory();
    }
    return p;
}

void *sim_grow(void *p, size_t count, size_t size)
{
    void *q;
    if ((size != 0U) && (count > (((size_t)-1) / size))) {
        out_of_memory();
    }
    q = realloc(p, ((count * size) == 0U) ? 1U : (count * size));
    if (q == NULL) {
        out_of_memory();
    }
    return q;
}

char *sim_strndup(const char *s, size_t n)
{
    char *p = (char *)sim_alloc(n + 1U);
    if (n > 0U) {
        (void)memcpy(p, s, n);
    }
    p[n] = '\0';
    return p;
}

/* ---- buffers ------------------------------------------------------------ */

void sim_buf_init(sim_buf *b)
{
    b->cap = 16U;
    b->p = (char *)sim_alloc(b->cap);
    b->len = 0U;
    b->p[0] = '\0';
}

void sim_buf_free(sim_buf *b)
{
    free(b->p);
    b->p = NULL;
    b->len = 0U;
    b->cap = 0U;
}

void sim_buf_clear(sim_buf *b)
{
    b->len = 0U;
    b->p[0] = '\0';
}

void sim_put(sim_buf *b, const char *s, size_t n)
{
    if ((b->len + n + 1U) > b->cap) {
        size_t cap = b->cap;
        while ((b->len + n + 1U) > cap) {
            cap *= 2U;
        }
        b->p = (char *)sim_grow(b->p, cap, 1U);
        b->cap = cap;
    }
    if (n > 0U) {
        (void)memcpy(&b->p[b->len], s, n);
    }
    b->len += n;
    b->p[b->len] = '\0';
}

void sim_puts(sim_buf *b, const char *s)
{
    sim_put(b, s, strlen(s));
}

void sim_putc(sim_buf *b, char c)
{
    sim_put(b, &c, 1U);
}

void sim_put_u64(sim_buf *b, uint64_t v)
{
    char tmp[24];
    size_t i = sizeof tmp;
    uint64_t x = v;
    do {
        i--;
        tmp[i] = (char)('0' + (int)(x % 10U));
        x /= 10U;
    } while (x != 0U);
    sim_put(b, &tmp[i], sizeof tmp - i);
}

static uint64_t magnitude(int64_t v)
{
    return (v < 0) ? ((uint64_t)0 - (uint64_t)v) : (uint64_t)v;
}

void sim_put_i64(sim_buf *b, int64_t v)
{
    if (v < 0) {
        sim_putc(b, '-');
    }
    sim_put_u64(b, magnitude(v));
}

void sim_put_i64_padded(sim_buf *b, int64_t v, size_t width)
{
    char tmp[24];
    size_t i = sizeof tmp;
    uint64_t x = magnitude(v);
    size_t used;
    do {
        i--;
        tmp[i] = (char)('0' + (int)(x % 10U));
        x /= 10U;
    } while (x != 0U);
    used = (sizeof tmp - i) + ((v < 0) ? 1U : 0U);
    if (v < 0) {
        sim_putc(b, '-');
    }
    while (used < width) {
        sim_putc(b, '0');
        used++;
    }
    sim_put(b, &tmp[i], sizeof tmp - i);
}

/* ---- UTF-8 ------------------------------------------------------------- */

size_t sim_utf8_next(const char *s, size_t n, uint32_t *cp)
{
    const unsigned char *u = (const unsigned char *)s;
    uint32_t c;
    size_t len;
    size_t i;
    uint32_t min;
    *cp = 0xFFFDU;
    if (n == 0U) {
        return 0U;
    }
    if (u[0] < 0x80U) {
        *cp = u[0];
        return 1U;
    } else if ((u[0] >= 0xC2U) && (u[0] <= 0xDFU)) {
        len = 2U;
        c = (uint32_t)u[0] & 0x1FU;
        min = 0x80U;
    } else if ((u[0] >= 0xE0U) && (u[0] <= 0xEFU)) {
        len = 3U;
        c = (uint32_t)u[0] & 0x0FU;
        min = 0x800U;
    } else if ((u[0] >= 0xF0U) && (u[0] <= 0xF4U)) {
        len = 4U;
        c = (uint32_t)u[0] & 0x07U;
        min = 0x10000U;
    } else {
        return 1U;
    }
    if (n < len) {
        return 1U;
    }
    for (i = 1U; i < len; i++) {
        if ((u[i] & 0xC0U) != 0x80U) {
            return 1U;
        }
        c = (c << 6) | ((uint32_t)u[i] & 0x3FU);
    }
    if ((c < min) || (c > 0x10FFFFU) || ((c >= 0xD800U) && (c <= 0xDFFFU))) {
        return 1U;
    }
    *cp = c;
    return len;
}

/* The length of a valid sequence at s, 0 when it is not valid. */
static size_t valid_len(const char *s, size_t n)
{
    uint32_t cp;
    size_t len = sim_utf8_next(s, n, &cp);
    if ((len == 1U) && (cp == 0xFFFDU)) {
        return 0U;
    }
    return len;
}

int sim_utf8_valid(const char *s, size_t n)
{
    size_t i = 0U;
    while (i < n) {
        size_t len = valid_len(&s[i], n - i);
        if (len == 0U) {
            return 0;
        }
        i += len;
    }
    return 1;
}

void sim_put_utf8(sim_buf *b, uint32_t cp)
{
    char t[4];
    if (cp < 0x80U) {
        t[0] = (char)cp;
        sim_put(b, t, 1U);
    } else if (cp < 0x800U) {
        t[0] = (char)(0xC0U | (cp >> 6));
        t[1] = (char)(0x80U | (cp & 0x3FU));
        sim_put(b, t, 2U);
    } else if (cp < 0x10000U) {
        t[0] = (char)(0xE0U | (cp >> 12));
        t[1] = (char)(0x80U | ((cp >> 6) & 0x3FU));
        t[2] = (char)(0x80U | (cp & 0x3FU));
        sim_put(b, t, 3U);
    } else {
        t[0] = (char)(0xF0U | (cp >> 18));
        t[1] = (char)(0x80U | ((cp >> 12) & 0x3FU));
        t[2] = (char)(0x80U | ((cp >> 6) & 0x3FU));
        t[3] = (char)(0x80U | (cp & 0x3FU));
        sim_put(b, t, 4U);
    }
}

void sim_put_lossy(sim_buf *b, const char *s, size_t n)
{
    size_t i = 0U;
    while (i < n) {
        size_t len = valid_len(&s[i], n - i);
        if (len == 0U) {
            /* One U+FFFD per maximal invalid prefix, as Rust does. */
            size_t skip = 1U;
            const unsigned char *u = (const unsigned char *)&s[i];
            size_t need = 0U;
            if ((u[0] >= 0xC2U) && (u[0] <= 0xDFU)) {
                need = 2U;
            } else if ((u[0] >= 0xE0U) && (u[0] <= 0xEFU)) {
                need = 3U;
            } else if ((u[0] >= 0xF0U) && (u[0] <= 0xF4U)) {
                need = 4U;
            } else {
                need = 1U;
            }
            while ((skip < need) && ((i + skip) < n)) {
                unsigned char c = u[skip];
                unsigned char lo = 0x80U;
                unsigned char hi = 0xBFU;
                if (skip == 1U) {
                    if (u[0] == 0xE0U) {
                        lo = 0xA0U;
                    } else if (u[0] == 0xEDU) {
                        hi = 0x9FU;
                    } else if (u[0] == 0xF0U) {
                        lo = 0x90U;
                    } else if (u[0] == 0xF4U) {
                        hi = 0x8FU;
                    } else {
                        /* any continuation byte */
                    }
                }
                if ((c < lo) || (c > hi)) {
                    break;
                }
                skip++;
            }
            sim_put_utf8(b, 0xFFFDU);
            i += skip;
        } else {
            sim_put(b, &s[i], len);
            i += len;
        }
    }
}

size_t sim_char_count(const char *s, size_t n)
{
    size_t i = 0U;
    size_t count = 0U;
    while (i < n) {
        uint32_t cp;
        i += sim_utf8_next(&s[i], n - i, &cp);
        count++;
    }
    return count;
}

int sim_is_space(uint32_t cp)
{
    return ((cp >= 0x09U) && (cp <= 0x0DU)) || (cp == 0x20U) || (cp == 0x85U) || (cp == 0xA0U) ||
           (cp == 0x1680U) || ((cp >= 0x2000U) && (cp <= 0x200AU)) || (cp == 0x2028U) ||
           (cp == 0x2029U) || (cp == 0x202FU) || (cp == 0x205FU) || (cp == 0x3000U);
}

void sim_trim(const char **s, size_t *n)
{
    const char *p = *s;
    size_t len = *n;
    while (len > 0U) {
        uint32_t cp;
        size_t k = sim_utf8_next(p, len, &cp);
        if (!sim_is_space(cp)) {
            break;
        }
        p = &p[k];
        len -= k;
    }
    while (len > 0U) {
        /* Find the start of the last character. */
        size_t start = len - 1U;
        uint32_t cp;
        while ((start > 0U) && ((((unsigned char)p[start]) & 0xC0U) == 0x80U) && ((len - start) < 4U)) {
            start--;
        }
        if ((sim_utf8_next(&p[start], len - start, &cp) != (len - start)) || !sim_is_space(cp)) {
            break;
        }
        len = start;
    }
    *s = p;
    *n = len;
}

static char ascii_lower(char c)
{
    return ((c >= 'A') && (c <= 'Z')) ? (char)(c - 'A' + 'a') : c;
}

int sim_ieq(const char *a, size_t an, const char *b, size_t bn)
{
    size_t i;
    if (an != bn) {
        return 0;
    }
    for (i = 0U; i < an; i++) {
        if (ascii_lower(a[i]) != ascii_lower(b[i])) {
            return 0;
        }
    }
    return 1;
}

int sim_ieq_z(const char *a, size_t an, const char *z)
{
    return sim_ieq(a, an, z, strlen(z));
}

/* The characters of Windows-1252 bytes 0x80..0x9F (the five undefined
   bytes stand for the C1 control of the same code). */
static const uint16_t cp1252_high[32] = {
    0x20ACU, 0x0081U, 0x201AU, 0x0192U, 0x201EU, 0x2026U, 0x2020U, 0x2021U,
    0x02C6U, 0x2030U, 0x0160U, 0x2039U, 0x0152U, 0x008DU, 0x017DU, 0x008FU,
    0x0090U, 0x2018U, 0x2019U, 0x201CU, 0x201DU, 0x2022U, 0x2013U, 0x2014U,
    0x02DCU, 0x2122U, 0x0161U, 0x203AU, 0x0153U, 0x009DU, 0x017EU, 0x0178U
};

uint32_t sim_cp1252_decode(uint8_t b)
{
    if ((b >= 0x80U) && (b <= 0x9FU)) {
        return cp1252_high[b - 0x80U];
    }
    return b;
}

int sim_cp1252_encode(uint32_t cp)
{
    size_t i;
    if ((cp <= 0x7FU) || ((cp >= 0xA0U) && (cp <= 0xFFU))) {
        return (int)cp;
    }
    for (i = 0U; i < 32U; i++) {
        if (cp1252_high[i] == cp) {
            return (int)(0x80U + i);
        }
    }
    return -1;
}

/* ---- durations and dates ------------------------------------------------ */

#define NS_PER_S 1000000000LL
#define NS_PER_D 86400000000000LL

void sim_fmt_duration(sim_buf *b, int64_t ns, int long_form)
{
    static const char *const units[7] = { "d", "h", "m", "s", "ms", "us", "ns" };
    static const uint64_t sizes[7] = {
        86400000000000ULL, 3600000000000ULL, 60000000000ULL, 1000000000ULL, 1000000ULL, 1000ULL, 1ULL
    };
    uint64_t v = magnitude(ns);
    size_t i;
    sim_puts(b, (long_form != 0) ? "LTIME#" : "T#");
    if (ns < 0) {
        sim_putc(b, '-');
    }
    if (v == 0U) {
        sim_puts(b, "0s");
        return;
    }
    for (i = 0U; i < 7U; i++) {
        uint64_t n = v / sizes[i];
        if (n > 0U) {
            sim_put_u64(b, n);
            sim_puts(b, units[i]);
            v -= n * sizes[i];
        }
    }
}

static int64_t div_floor(int64_t a, int64_t b)
{
    int64_t q = a / b;
    if (((a % b) != 0) && ((a < 0) != (b < 0))) {
        q--;
    }
    return q;
}

static int64_t rem_floor(int64_t a, int64_t b)
{
    int64_t r = a % b;
    if (r < 0) {
        r += b;
    }
    return r;
}

/* The date of a day count since 1970-01-01 (stc_syntax civil_from_days). */
static void civil_from_days(int64_t days, int64_t *year, int64_t *month, int64_t *day)
{
    int64_t z = days + 719468;
    int64_t era = div_floor(z, 146097);
    int64_t doe = z - (era * 146097);
    int64_t yoe = (doe - (doe / 1460) + (doe / 36524) - (doe / 146096)) / 365;
    int64_t y = yoe + (era * 400);
    int64_t doy = doe - ((365 * yoe) + (yoe / 4) - (yoe / 100));
    int64_t mp = ((5 * doy) + 2) / 153;
    int64_t d = (doy - (((153 * mp) + 2) / 5)) + 1;
    int64_t m = (mp < 10) ? (mp + 3) : (mp - 9);
    *year = (m <= 2) ? (y + 1) : y;
    *month = m;
    *day = d;
}

static void put_ymd(sim_buf *b, int64_t days)
{
    int64_t y;
    int64_t m;
    int64_t d;
    civil_from_days(days, &y, &m, &d);
    sim_put_i64_padded(b, y, 4U);
    sim_putc(b, '-');
    sim_put_i64_padded(b, m, 2U);
    sim_putc(b, '-');
    sim_put_i64_padded(b, d, 2U);
}

/* hh:mm:ss[.fraction] of nanoseconds since midnight (0 <= ns < a day). */
static void put_tod(sim_buf *b, int64_t ns)
{
    int64_t frac = ns % NS_PER_S;
    sim_put_i64_padded(b, ns / 3600000000000LL, 2U);
    sim_putc(b, ':');
    sim_put_i64_padded(b, (ns / 60000000000LL) % 60, 2U);
    sim_putc(b, ':');
    sim_put_i64_padded(b, (ns / NS_PER_S) % 60, 2U);
    if (frac > 0) {
        char digits[9];
        size_t i;
        size_t n = 9U;
        int64_t f = frac;
        for (i = 9U; i > 0U; i--) {
            digits[i - 1U] = (char)('0' + (int)(f % 10));
            f /= 10;
        }
        while ((n > 0U) && (digits[n - 1U] == '0')) {
            n--;
        }
        sim_putc(b, '.');
        sim_put(b, digits, n);
    }
}

void sim_fmt_date(sim_buf *b, int64_t secs, int long_form)
{
    sim_puts(b, (long_form != 0) ? "LDATE#" : "D#");
    put_ymd(b, div_floor(secs, 86400));
}

void sim_fmt_tod(sim_buf *b, int64_t ns, int long_form)
{
    sim_puts(b, (long_form != 0) ? "LTOD#" : "TOD#");
    put_tod(b, rem_floor(ns, NS_PER_D));
}

void sim_fmt_dt(sim_buf *b, int64_t ns, int long_form)
{
    sim_puts(b, (long_form != 0) ? "LDT#" : "DT#");
    put_ymd(b, div_floor(ns, NS_PER_D));
    sim_putc(b, '-');
    put_tod(b, rem_floor(ns, NS_PER_D));
}

/* ---- REAL numbers -------------------------------------------------------- */

/* Whether the decimal text reads back as x (as a float when single). */
static int reads_back(const char *text, double x, int single, int *above)
{
    if (single != 0) {
        float f = strtof(text, NULL);
        float want = (float)x;
        *above = (f > want) ? 1 : 0;
        return (f == want) ? 1 : 0;
    } else {
        double d = strtod(text, NULL);
        *above = (d > x) ? 1 : 0;
        return (d == x) ? 1 : 0;
    }
}

/* Writes d[0].d[1..n)e<exp> into t. */
static void sci_text(char *t, size_t size, const char *d, size_t n, int exp10)
{
    char mant[24];
    size_t i;
    size_t k = 0U;
    mant[k] = d[0];
    k++;
    if (n > 1U) {
        mant[k] = '.';
        k++;
        for (i = 1U; i < n; i++) {
            mant[k] = d[i];
            k++;
        }
    }
    mant[k] = '\0';
    (void)snprintf(t, size, "%se%d", mant, exp10);
}

/* Adds (+1) or subtracts (-1) one unit in the last of n digits; the
   exponent follows a carry or borrow over a power of ten. */
static void step_digits(char *d, size_t n, int *exp10, int dir)
{
    size_t i = n;
    if (dir > 0) {
        while (i > 0U) {
            i--;
            if (d[i] == '9') {
                d[i] = '0';
            } else {
                d[i] = (char)(d[i] + 1);
                return;
            }
        }
        /* 9.99 + 0.01 = 10.0: 1.00 with the next exponent. */
        d[0] = '1';
        *exp10 += 1;
    } else {
        while (i > 0U) {
            i--;
            if (d[i] == '0') {
                d[i] = '9';
            } else {
                d[i] = (char)(d[i] - 1);
                break;
            }
        }
        if (d[0] == '0') {
            /* 1.00 - 0.01 = 0.99: 9.99 with the previous exponent. */
            for (i = 0U; i < n; i++) {
                d[i] = '9';
            }
            *exp10 -= 1;
        }
    }
}

/* Whether x (> 0) lies exactly halfway between two decimals of p
   significant digits; then `lower` gets the lower one's p digits and
   `*exp10` its exponent. */
static int exact_tie(double x, int p, char *lower, int *exp10)
{
    char t[48];
    char exact[820];
    const char *q;
    size_t n = 0U;
    /* Cheap test first: p + 1 digits ending in 5. */
    (void)snprintf(t, sizeof t, "%.*e", p, x);
    q = strchr(t, 'e');
    if ((q == NULL) || (q == t) || (q[-1] != '5')) {
        return 0;
    }
    /* The exact expansion (a double has at most 767 significant digits). */
    (void)snprintf(exact, sizeof exact, "%.*e", 790, x);
    for (q = exact; (*q != 'e') && (*q != '\0'); q++) {
        if ((*q >= '0') && (*q <= '9')) {
            if (n < (size_t)p) {
                lower[n] = *q;
            } else if (n == (size_t)p) {
                if (*q != '5') {
                    return 0;
                }
            } else if (*q != '0') {
                return 0;
            } else {
                /* a trailing zero */
            }
            n++;
        }
    }
    *exp10 = (*q == 'e') ? atoi(&q[1]) : 0;
    return 1;
}

/* The shortest digits (no trailing zeros) that read back as x > 0, and the
   exponent e with x = d.ddd * 10^e; among the shortest, the closest, and
   at an exact tie the upper one (`ties_up`, Rust's Debug) or the even one
   (glibc's rounding, as serde_json prints). */
static size_t shortest_digits(double x, int single, int ties_up, char *digits, int *exp10)
{
    char text[48];
    int maxp = (single != 0) ? 9 : 17;
    int p;
    for (p = 1; p <= maxp; p++) {
        char d[24];
        size_t n = 0U;
        size_t i;
        int e;
        int above = 0;
        int found = 0;
        const char *q;
        if (ties_up != 0) {
            char lo[24];
            int elo = 0;
            if (exact_tie(x, p, lo, &elo) != 0) {
                /* The upper candidate if it reads back, else the lower. */
                for (i = 0U; i < (size_t)p; i++) {
                    d[i] = lo[i];
                }
                n = (size_t)p;
                e = elo;
                step_digits(d, n, &e, 1);
                sci_text(text, sizeof text, d, n, e);
                found = reads_back(text, x, single, &above);
                if (found == 0) {
                    for (i = 0U; i < (size_t)p; i++) {
                        d[i] = lo[i];
                    }
                    e = elo;
                    sci_text(text, sizeof text, d, n, e);
                    found = reads_back(text, x, single, &above);
                }
                if (found == 0) {
                    continue;
                }
            }
        }
        if (found == 0) {
            (void)snprintf(text, sizeof text, "%.*e", p - 1, x);
            n = 0U;
            for (q = text; (*q != 'e') && (*q != '\0'); q++) {
                if ((*q >= '0') && (*q <= '9')) {
                    d[n] = *q;
                    n++;
                }
            }
            e = (*q == 'e') ? atoi(&q[1]) : 0;
            if (reads_back(text, x, single, &above) == 0) {
                /* The correctly rounded digits miss the interval; only the
                   neighbour on the other side of x can be in it. */
                int e2 = e;
                step_digits(d, n, &e2, (above != 0) ? -1 : 1);
                sci_text(text, sizeof text, d, n, e2);
                if (reads_back(text, x, single, &above) == 0) {
                    continue;
                }
                e = e2;
            }
        }
        while ((n > 1U) && (d[n - 1U] == '0')) {
            n--;
        }
        for (i = 0U; i < n; i++) {
            digits[i] = d[i];
        }
        *exp10 = e;
        return n;
    }
    /* Not reached for finite x: 17 (9) digits always read back. */
    (void)snprintf(text, sizeof text, "%.16e", x);
    digits[0] = text[0];
    *exp10 = 0;
    return 1U;
}

/* Decimal notation of d.ddd * 10^e; `frac0` adds ".0" to integers. */
static void put_decimal(sim_buf *b, const char *d, size_t n, int e)
{
    size_t i;
    if (e >= 0) {
        size_t int_digits = (size_t)e + 1U;
        for (i = 0U; i < int_digits; i++) {
            sim_putc(b, (i < n) ? d[i] : '0');
        }
        sim_putc(b, '.');
        if (n > int_digits) {
            sim_put(b, &d[int_digits], n - int_digits);
        } else {
            sim_putc(b, '0');
        }
    } else {
        sim_puts(b, "0.");
        for (i = 1U; i < (size_t)(-e); i++) {
            sim_putc(b, '0');
        }
        sim_put(b, d, n);
    }
}

void sim_fmt_real(sim_buf *b, double x, int single, int json)
{
    char d[24];
    size_t n;
    int e;
    double ax;
    if (isnan(x)) {
        sim_puts(b, (json != 0) ? "\"NaN\"" : "NaN");
        return;
    }
    if (isinf(x)) {
        if (x > 0.0) {
            sim_puts(b, (json != 0) ? "\"INF\"" : "INF");
        } else {
            sim_puts(b, (json != 0) ? "\"-INF\"" : "-INF");
        }
        return;
    }
    if (signbit(x) != 0) {
        sim_putc(b, '-');
    }
    ax = fabs(x);
    if (ax == 0.0) {
        sim_puts(b, "0.0");
        return;
    }
    n = shortest_digits(ax, single, (json != 0) ? 0 : 1, d, &e);
    if (json != 0) {
        /* serde_json (zmij): fixed notation for exponents -5..=15 (f64)
           or -6..=12 (f32), else `d.ddde+N` / `de-N`. */
        int lo = (single != 0) ? -6 : -5;
        int hi = (single != 0) ? 12 : 15;
        if ((e >= lo) && (e <= hi)) {
            put_decimal(b, d, n, e);
        } else {
            sim_putc(b, d[0]);
            if (n > 1U) {
                sim_putc(b, '.');
                sim_put(b, &d[1], n - 1U);
            }
            sim_putc(b, 'e');
            sim_putc(b, (e < 0) ? '-' : '+');
            sim_put_i64(b, (e < 0) ? -(int64_t)e : (int64_t)e);
        }
    } else {
        /* Rust's Debug: fixed notation for 1e-4 <= |x| < 1e16, else
           `d.dddeN`; stc's format_real then writes `d.dddEN` with a `.0`
           on a one-digit mantissa. */
        if ((e >= -4) && (e <= 15)) {
            put_decimal(b, d, n, e);
        } else {
            sim_putc(b, d[0]);
            sim_putc(b, '.');
            if (n > 1U) {
                sim_put(b, &d[1], n - 1U);
            } else {
                sim_putc(b, '0');
            }
            sim_putc(b, 'E');
            sim_put_i64(b, (int64_t)e);
        }
    }
}

/* ---- strings ------------------------------------------------------------- */

void sim_json_string(sim_buf *b, const char *s, size_t n)
{
    static const char hex[] = "0123456789abcdef";
    size_t i;
    sim_putc(b, '"');
    for (i = 0U; i < n; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c == (unsigned char)'"') {
            sim_puts(b, "\\\"");
        } else if (c == (unsigned char)'\\') {
            sim_puts(b, "\\\\");
        } else if (c == 0x08U) {
            sim_puts(b, "\\b");
        } else if (c == 0x0CU) {
            sim_puts(b, "\\f");
        } else if (c == (unsigned char)'\n') {
            sim_puts(b, "\\n");
        } else if (c == (unsigned char)'\r') {
            sim_puts(b, "\\r");
        } else if (c == (unsigned char)'\t') {
            sim_puts(b, "\\t");
        } else if (c < 0x20U) {
            sim_puts(b, "\\u00");
            sim_putc(b, hex[c >> 4]);
            sim_putc(b, hex[c & 0x0FU]);
        } else {
            sim_putc(b, (char)c);
        }
    }
    sim_putc(b, '"');
}

void sim_st_string(sim_buf *b, const uint32_t *cps, size_t n, int wide)
{
    static const char hex[] = "0123456789ABCDEF";
    char quote = (wide != 0) ? '"' : '\'';
    size_t i;
    sim_putc(b, quote);
    for (i = 0U; i < n; i++) {
        uint32_t c = cps[i];
        if (c == (uint32_t)'$') {
            sim_puts(b, "$$");
        } else if (c == (uint32_t)'\n') {
            sim_puts(b, "$N");
        } else if (c == (uint32_t)'\r') {
            sim_puts(b, "$R");
        } else if (c == (uint32_t)'\t') {
            sim_puts(b, "$T");
        } else if (c == 0x0CU) {
            sim_puts(b, "$P");
        } else if (c == (uint32_t)(unsigned char)quote) {
            sim_putc(b, '$');
            sim_putc(b, quote);
        } else if ((c < 0x20U) || (c == 0x7FU)) {
            sim_putc(b, '$');
            if (wide != 0) {
                sim_putc(b, '0');
                sim_putc(b, '0');
            }
            sim_putc(b, hex[(c >> 4) & 0x0FU]);
            sim_putc(b, hex[c & 0x0FU]);
        } else {
            sim_put_utf8(b, c);
        }
    }
    sim_putc(b, quote);
}

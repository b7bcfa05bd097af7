/*
 * stc_sim_path.c - variable paths (a port of stc_runtime's path.rs):
 * `instance.var` followed by `.member`, `[i,j]` or `[i][j]`, a global by
 * its plain name, or a direct address such as `%QX0.0`. Names match
 * case-insensitively; a resolved place carries the declared spelling.
 * References on the way (VAR_EXTERNAL, VAR_IN_OUT, located variables) are
 * followed each time the place is read or written.
 */
#include "stc_sim.h"

#include <stdlib.h>
#include <string.h>

/* ---- direct addresses ---------------------------------------------------- */

typedef struct {
    char area;              /* 'I', 'Q', 'M' */
    char size;              /* 'X', 'B', 'W', 'D', 'L' */
    int explicit_size;
    uint32_t *path;         /* empty for `%I*` */
    size_t npath;
} sim_addr;

static char upper(char c)
{
    return ((c >= 'a') && (c <= 'z')) ? (char)(c - 'a' + 'A') : c;
}

static int is_digit(char c)
{
    return (c >= '0') && (c <= '9');
}

static int is_alpha(char c)
{
    return ((c >= 'a') && (c <= 'z')) || ((c >= 'A') && (c <= 'Z'));
}

static void addr_free(sim_addr *a)
{
    free(a->path);
    a->path = NULL;
    a->npath = 0U;
}

/* stc_syntax parse_address: `%IX1.2`, `%QW4`, `%MD12`, `%I*`. */
static int parse_address(const char *t, size_t n, sim_addr *a, sim_buf *err)
{
    char c1 = (n > 1U) ? upper(t[1]) : '\0';
    char c2 = (n > 2U) ? upper(t[2]) : '\0';
    const char *rest;
    size_t rn;
    size_t i;
    a->path = NULL;
    a->npath = 0U;
    if ((c1 != 'I') && (c1 != 'Q') && (c1 != 'M')) {
        sim_puts(err, "invalid direct address `");
        sim_put(err, t, n);
        sim_puts(err, "`: the location must be I, Q or M");
        return 0;
    }
    a->area = c1;
    if ((c2 == 'X') || (c2 == 'B') || (c2 == 'W') || (c2 == 'D') || (c2 == 'L')) {
        a->size = c2;
        a->explicit_size = 1;
        rest = &t[3];
        rn = n - 3U;
    } else {
        a->size = 'X';
        a->explicit_size = 0;
        rest = &t[2];
        rn = n - 2U;
    }
    if ((rn == 1U) && (rest[0] == '*')) {
        return 1;
    }
    a->path = (uint32_t *)sim_alloc((rn + 1U) * sizeof(uint32_t));
    i = 0U;
    for (;;) {
        uint64_t v = 0U;
        size_t start = i;
        while ((i < rn) && (rest[i] != '.')) {
            if ((is_digit(rest[i]) == 0) || (v > 0xFFFFFFFFU)) {
                break;
            }
            v = (v * 10U) + (uint64_t)(rest[i] - '0');
            i++;
        }
        if ((i == start) || ((i < rn) && (rest[i] != '.')) || (v > 0xFFFFFFFFU)) {
            addr_free(a);
            sim_puts(err, "invalid direct address `");
            sim_put(err, t, n);
            sim_puts(err, "`: expected numbers separated by dots, as in %IX0.1");
            return 0;
        }
        a->path[a->npath] = (uint32_t)v;
        a->npath++;
        if (i >= rn) {
            break;
        }
        i++; /* the dot */
    }
    return 1;
}

static void addr_display(sim_buf *b, const sim_addr *a)
{
    size_t i;
    sim_putc(b, '%');
    sim_putc(b, a->area);
    if (a->explicit_size != 0) {
        sim_putc(b, a->size);
    }
    if (a->npath == 0U) {
        sim_putc(b, '*');
        return;
    }
    for (i = 0U; i < a->npath; i++) {
        if (i > 0U) {
            sim_putc(b, '.');
        }
        sim_put_u64(b, a->path[i]);
    }
}

static int addr_same(const sim_addr *a, const sim_addr *b, int exact)
{
    size_t i;
    if ((a->area != b->area) || (a->size != b->size) || (a->npath != b->npath)) {
        return 0;
    }
    if ((exact != 0) && (a->explicit_size != b->explicit_size)) {
        return 0;
    }
    for (i = 0U; i < a->npath; i++) {
        if (a->path[i] != b->path[i]) {
            return 0;
        }
    }
    return 1;
}

char sim_location_area(const char *loc)
{
    if ((loc == NULL) || (loc[0] != '%') || (loc[1] == '\0')) {
        return '\0';
    }
    return upper(loc[1]);
}

/* ---- integers of paths ---------------------------------------------------- */

static int digit_value(char c, uint32_t base, uint32_t *d)
{
    uint32_t v;
    if (is_digit(c) != 0) {
        v = (uint32_t)(c - '0');
    } else if ((c >= 'a') && (c <= 'z')) {
        v = (uint32_t)(c - 'a') + 10U;
    } else if ((c >= 'A') && (c <= 'Z')) {
        v = (uint32_t)(c - 'A') + 10U;
    } else {
        return 0;
    }
    if (v >= base) {
        return 0;
    }
    *d = v;
    return 1;
}

/* stc_syntax digits_value: digits with single `_` separators. */
static int digits_value(const char *s, size_t n, uint32_t base, uint64_t *out)
{
    uint64_t v = 0U;
    int overflow = 0;
    size_t i;
    if (n == 0U) {
        return 0;
    }
    if ((s[0] == '_') || (s[n - 1U] == '_')) {
        return 0;
    }
    for (i = 0U; (i + 1U) < n; i++) {
        if ((s[i] == '_') && (s[i + 1U] == '_')) {
            return 0;
        }
    }
    for (i = 0U; i < n; i++) {
        uint32_t d;
        if (s[i] == '_') {
            continue;
        }
        if (digit_value(s[i], base, &d) == 0) {
            return 0;
        }
        if ((v > ((UINT64_MAX - d) / base))) {
            overflow = 1;
        } else {
            v = (v * base) + d;
        }
    }
    if (overflow != 0) {
        return 0;
    }
    *out = v;
    return 1;
}

/* An index: decimal or `16#..`, with an optional sign and `_`. */
static int parse_index(const char *s, size_t n, int64_t *out)
{
    int negative = 0;
    const char *d = s;
    size_t dn = n;
    uint64_t mag;
    const char *hash;
    if ((dn > 0U) && (d[0] == '-')) {
        negative = 1;
        d = &d[1];
        dn--;
    } else if ((dn > 0U) && (d[0] == '+')) {
        d = &d[1];
        dn--;
    } else {
        /* unsigned */
    }
    hash = (const char *)memchr(d, '#', dn);
    if (hash != NULL) {
        /* parse_based_int: the base (2, 8 or 16; `_` ignored, `+` allowed),
           then digits of that base. */
        size_t bn = (size_t)(hash - d);
        size_t i;
        uint64_t base = 0U;
        size_t digits = 0U;
        size_t seen = 0U;
        for (i = 0U; i < bn; i++) {
            if (d[i] == '_') {
                continue;
            }
            if ((seen == 0U) && (d[i] == '+')) {
                seen++;
                continue;
            }
            seen++;
            if (is_digit(d[i]) == 0) {
                return 0;
            }
            if (base < 1000U) {
                base = (base * 10U) + (uint64_t)(d[i] - '0');
            }
            digits++;
        }
        if ((digits == 0U) || ((base != 2U) && (base != 8U) && (base != 16U))) {
            return 0;
        }
        if (digits_value(&hash[1], dn - bn - 1U, (uint32_t)base, &mag) == 0) {
            return 0;
        }
    } else {
        size_t i;
        for (i = 0U; i < dn; i++) {
            if ((is_digit(d[i]) == 0) && (d[i] != '_')) {
                return 0;
            }
        }
        if (digits_value(d, dn, 10U, &mag) == 0) {
            return 0;
        }
    }
    if (negative != 0) {
        if (mag > ((uint64_t)INT64_MAX + 1U)) {
            return 0;
        }
        *out = (mag == ((uint64_t)INT64_MAX + 1U)) ? INT64_MIN : -(int64_t)mag;
    } else {
        if (mag > (uint64_t)INT64_MAX) {
            return 0;
        }
        *out = (int64_t)mag;
    }
    return 1;
}

/* ---- parsing paths -------------------------------------------------------- */

typedef struct {
    int is_index;
    const char *name;       /* member */
    size_t nlen;
    int64_t *idx;           /* index */
    size_t nidx;
} sim_seg;

typedef struct {
    int is_addr;
    sim_addr addr;
    const char *root;
    size_t rlen;
    sim_seg *segs;
    size_t nsegs;
} sim_path;

static void path_free(sim_path *p)
{
    size_t i;
    for (i = 0U; i < p->nsegs; i++) {
        free(p->segs[i].idx);
    }
    free(p->segs);
    p->segs = NULL;
    p->nsegs = 0U;
    if (p->is_addr != 0) {
        addr_free(&p->addr);
    }
}

static void bad_path(sim_buf *err, const char *text, size_t n, const char *why)
{
    sim_puts(err, "invalid path `");
    sim_put(err, text, n);
    sim_puts(err, "`: ");
    sim_puts(err, why);
}

/* A name: [A-Za-z_][A-Za-z0-9_]*; its length, 0 when there is none. */
static size_t name_len(const char *s, size_t n)
{
    size_t i = 0U;
    if ((n == 0U) || ((is_alpha(s[0]) == 0) && (s[0] != '_'))) {
        return 0U;
    }
    while ((i < n) && ((is_alpha(s[i]) != 0) || (is_digit(s[i]) != 0) || (s[i] == '_'))) {
        i++;
    }
    return i;
}

static int parse_path(const char *text, size_t n, sim_path *p, sim_buf *err)
{
    const char *t = text;
    size_t tn = n;
    size_t i;
    size_t k;
    (void)memset(p, 0, sizeof *p);
    p->segs = NULL;
    p->root = NULL;
    p->addr.path = NULL;
    sim_trim(&t, &tn);
    if (tn == 0U) {
        bad_path(err, text, n, "it is empty");
        return 0;
    }
    if (t[0] == '%') {
        for (i = 0U; i < tn; i++) {
            if ((((unsigned char)t[i]) & 0x80U) != 0U) {
                bad_path(err, text, n, "a direct address is written like %IX0.1 or %QW4");
                return 0;
            }
        }
        if (parse_address(t, tn, &p->addr, err) == 0) {
            return 0;
        }
        p->is_addr = 1;
        if (p->addr.npath == 0U) {
            path_free(p);
            bad_path(err, text, n, "`*` addresses have no storage");
            return 0;
        }
        return 1;
    }
    k = name_len(t, tn);
    if (k == 0U) {
        bad_path(err, text, n, "expected a name at its start");
        return 0;
    }
    p->root = t;
    p->rlen = k;
    i = k;
    p->segs = (sim_seg *)sim_alloc((tn + 1U) * sizeof(sim_seg));
    while (i < tn) {
        sim_seg *s = &p->segs[p->nsegs];
        s->idx = NULL;
        s->nidx = 0U;
        s->is_index = 0;
        if (t[i] == '.') {
            i++;
            k = name_len(&t[i], tn - i);
            if (k == 0U) {
                path_free(p);
                bad_path(err, text, n, "expected a name after `.`");
                return 0;
            }
            s->name = &t[i];
            s->nlen = k;
            p->nsegs++;
            i += k;
        } else if (t[i] == '[') {
            const char *close = (const char *)memchr(&t[i], ']', tn - i);
            const char *inner;
            size_t in_n;
            size_t pos = 0U;
            if (close == NULL) {
                path_free(p);
                bad_path(err, text, n, "`[` is not closed");
                return 0;
            }
            inner = &t[i + 1U];
            in_n = (size_t)(close - inner);
            s->is_index = 1;
            s->idx = (int64_t *)sim_alloc((in_n + 1U) * sizeof(int64_t));
            p->nsegs++;
            for (;;) {
                const char *comma = (const char *)memchr(&inner[pos], ',', in_n - pos);
                size_t end = (comma != NULL) ? (size_t)(comma - inner) : in_n;
                const char *part = &inner[pos];
                size_t pn = end - pos;
                sim_trim(&part, &pn);
                if (parse_index(part, pn, &s->idx[s->nidx]) == 0) {
                    sim_buf why;
                    sim_buf_init(&why);
                    sim_putc(&why, '`');
                    sim_put(&why, part, pn);
                    sim_puts(&why, "` is not an integer index");
                    path_free(p);
                    bad_path(err, text, n, why.p);
                    sim_buf_free(&why);
                    return 0;
                }
                s->nidx++;
                if (comma == NULL) {
                    break;
                }
                pos = end + 1U;
            }
            i = (size_t)(close - t) + 1U;
        } else {
            uint32_t cp;
            size_t len = sim_utf8_next(&t[i], tn - i, &cp);
            sim_buf why;
            sim_buf_init(&why);
            sim_puts(&why, "unexpected `");
            sim_put(&why, &t[i], len);
            sim_putc(&why, '`');
            path_free(p);
            bad_path(err, text, n, why.p);
            sim_buf_free(&why);
            return 0;
        }
    }
    return 1;
}

/* ---- places ----------------------------------------------------------------- */

void sim_place_free(sim_place *p)
{
    sim_buf_free(&p->name);
    free(p->steps);
    p->steps = NULL;
    p->nsteps = 0U;
}

static void place_init(sim_place *p, unsigned char *base, uint32_t type)
{
    sim_buf_init(&p->name);
    p->base = base;
    p->steps = NULL;
    p->nsteps = 0U;
    p->view.slice = 0;
    p->view.type = type;
    p->view.dims = NULL;
    p->view.ndims = 0U;
    p->view.stride = 0U;
    p->constant = 0;
}

static void push_step(sim_place *p, uint8_t deref, size_t add)
{
    p->steps = (sim_step *)sim_grow(p->steps, p->nsteps + 1U, sizeof(sim_step));
    p->steps[p->nsteps].deref = deref;
    p->steps[p->nsteps].add = add;
    p->nsteps++;
}

static void loc_add(sim_place *p, size_t n)
{
    if (p->nsteps == 0U) {
        if (p->base != NULL) {
            p->base = &p->base[n];
        }
    } else if (p->steps[p->nsteps - 1U].deref == 0U) {
        p->steps[p->nsteps - 1U].add += n;
    } else {
        push_step(p, 0U, n);
    }
}

unsigned char *sim_place_addr(const sim_place *p)
{
    unsigned char *a = p->base;
    size_t i;
    for (i = 0U; i < p->nsteps; i++) {
        if (a == NULL) {
            return NULL;
        }
        if (p->steps[i].deref != 0U) {
            void *q;
            (void)memcpy(&q, a, sizeof q);
            a = (unsigned char *)q;
        } else {
            a = &a[p->steps[i].add];
        }
    }
    return a;
}

static void unknown_variable(sim_buf *err, const char *t, size_t tn)
{
    sim_puts(err, "unknown variable `");
    sim_put(err, t, tn);
    sim_puts(err, "`: ");
}

static int resolve_address(const sim_addr *a, const char *t, size_t tn, sim_place *out, sim_buf *err)
{
    uint32_t k;
    int pass;
    for (pass = 1; pass >= 0; pass--) {
        for (k = 0U; k < stc_n_io; k++) {
            sim_addr slot;
            sim_buf ignore;
            int ok;
            const char *s = stc_io[k].address;
            sim_buf_init(&ignore);
            ok = (s != NULL) ? parse_address(s, strlen(s), &slot, &ignore) : 0;
            sim_buf_free(&ignore);
            if (ok == 0) {
                continue;
            }
            if (addr_same(a, &slot, pass) != 0) {
                addr_free(&slot);
                place_init(out, (unsigned char *)stc_io[k].data, stc_io[k].type);
                addr_display(&out->name, a);
                return 1;
            }
            addr_free(&slot);
        }
    }
    sim_puts(err, "unknown address `");
    sim_put(err, t, tn);
    sim_puts(err, "`: the program uses no variable at ");
    addr_display(err, a);
    return 0;
}

static int resolve_root(const sim_scope *sc, const char *r, size_t rn, const char *t, size_t tn,
                        sim_place *out, sim_buf *err)
{
    size_t i;
    uint32_t k;
    const stc_global *found = NULL;
    for (i = 0U; i < sc->ninst; i++) {
        const stc_program *p = sc->inst[i];
        if (sim_ieq_z(r, rn, p->name) != 0) {
            const stc_type *d = sim_type(p->type);
            if ((d == NULL) || (d->kind != (uint8_t)STC_TK_INSTANCE)) {
                sim_puts(err, "program instance `");
                sim_puts(err, p->name);
                sim_puts(err, "` has no code");
                return 0;
            }
            place_init(out, (unsigned char *)p->data, p->type);
            sim_puts(&out->name, p->name);
            return 1;
        }
    }
    /* A global of the chosen configuration, else a top-level one, else any. */
    for (k = 0U; (k < stc_n_globals) && (found == NULL); k++) {
        if ((sim_ieq_z(r, rn, stc_globals[k].name) != 0) && (stc_globals[k].config >= 0) &&
            (stc_globals[k].config == sc->config)) {
            found = &stc_globals[k];
        }
    }
    for (k = 0U; (k < stc_n_globals) && (found == NULL); k++) {
        if ((sim_ieq_z(r, rn, stc_globals[k].name) != 0) && (stc_globals[k].config < 0)) {
            found = &stc_globals[k];
        }
    }
    for (k = 0U; (k < stc_n_globals) && (found == NULL); k++) {
        if (sim_ieq_z(r, rn, stc_globals[k].name) != 0) {
            found = &stc_globals[k];
        }
    }
    if (found != NULL) {
        place_init(out, (unsigned char *)found->data, found->type);
        sim_puts(&out->name, found->name);
        out->constant = (found->constant != 0U) ? 1 : 0;
        return 1;
    }
    unknown_variable(err, t, tn);
    sim_putc(err, '`');
    sim_put(err, r, rn);
    sim_puts(err, "` is neither a program instance (");
    if (sc->ninst == 0U) {
        sim_puts(err, "there are none");
    }
    for (i = 0U; i < sc->ninst; i++) {
        if (i > 0U) {
            sim_puts(err, ", ");
        }
        sim_puts(err, sc->inst[i]->name);
    }
    sim_puts(err, ") nor a global variable");
    return 0;
}

static void no_member(sim_buf *err, const char *t, size_t tn, const sim_place *p, const char *what,
                      const char *m, size_t mn)
{
    unknown_variable(err, t, tn);
    sim_putc(err, '`');
    sim_put(err, p->name.p, p->name.len);
    sim_putc(err, '`');
    if (what != NULL) {
        sim_puts(err, what);
    }
    sim_puts(err, " has no member `");
    sim_put(err, m, mn);
    sim_putc(err, '`');
}

static int resolve_member(sim_place *p, const char *m, size_t mn, const char *t, size_t tn, sim_buf *err)
{
    const stc_type *d;
    uint32_t k;
    if (p->view.slice != 0) {
        no_member(err, t, tn, p, " (ARRAY)", m, mn);
        return 0;
    }
    d = sim_type(p->view.type);
    if ((d != NULL) && (d->kind == (uint8_t)STC_TK_STRUCT)) {
        for (k = 0U; k < d->count; k++) {
            const stc_member *f = &d->members[k];
            if (sim_ieq_z(m, mn, f->name) != 0) {
                sim_putc(&p->name, '.');
                sim_puts(&p->name, f->name);
                loc_add(p, f->offset);
                p->view.type = f->type;
                return 1;
            }
        }
        no_member(err, t, tn, p, NULL, m, mn);
        return 0;
    }
    if ((d != NULL) && (d->kind == (uint8_t)STC_TK_INSTANCE)) {
        for (k = 0U; k < d->count; k++) {
            const stc_member *v = &d->members[k];
            if ((v->kind != (uint8_t)STC_VK_HIDDEN) && (sim_ieq_z(m, mn, v->name) != 0)) {
                if (v->kind == (uint8_t)STC_VK_TEMP) {
                    sim_putc(err, '`');
                    sim_put(err, p->name.p, p->name.len);
                    sim_putc(err, '.');
                    sim_puts(err, v->name);
                    sim_puts(err, "` is a temporary variable: it exists only while its POU runs");
                    return 0;
                }
                sim_putc(&p->name, '.');
                sim_puts(&p->name, v->name);
                loc_add(p, v->offset);
                if (v->is_ref != 0U) {
                    push_step(p, 1U, 0U);
                }
                p->view.type = v->type;
                if (v->constant != 0U) {
                    p->constant = 1;
                }
                return 1;
            }
        }
        no_member(err, t, tn, p, NULL, m, mn);
        return 0;
    }
    {
        sim_buf what;
        sim_buf_init(&what);
        sim_puts(&what, " (");
        sim_describe(&what, p->view.type);
        sim_putc(&what, ')');
        no_member(err, t, tn, p, what.p, m, mn);
        sim_buf_free(&what);
    }
    return 0;
}

static int mul_add(uint64_t *acc, uint64_t mul, uint64_t add)
{
    if ((mul != 0U) && (*acc > (UINT64_MAX / mul))) {
        return 0;
    }
    *acc *= mul;
    if (*acc > (UINT64_MAX - add)) {
        return 0;
    }
    *acc += add;
    return 1;
}

static int resolve_index(sim_place *p, const int64_t *ix, size_t nix, const char *t, size_t tn, sim_buf *err)
{
    size_t left = 0U;
    size_t i;
    while (left < nix) {
        uint32_t elem;
        const stc_dim *dims;
        uint32_t ndims;
        size_t stride;
        size_t take;
        uint32_t d;
        uint64_t flat = 0U;
        if (p->view.slice != 0) {
            elem = p->view.type;
            dims = p->view.dims;
            ndims = p->view.ndims;
            stride = p->view.stride;
        } else {
            const stc_type *ty = sim_type(p->view.type);
            if ((ty == NULL) || (ty->kind != (uint8_t)STC_TK_ARRAY)) {
                unknown_variable(err, t, tn);
                sim_putc(err, '`');
                sim_put(err, p->name.p, p->name.len);
                sim_puts(err, "` (");
                sim_describe(err, p->view.type);
                sim_puts(err, ") is not an array");
                return 0;
            }
            elem = ty->elem_type;
            dims = ty->dims;
            ndims = ty->count;
            stride = ty->stride;
        }
        take = ((nix - left) < (size_t)ndims) ? (nix - left) : (size_t)ndims;
        if (take == 0U) {
            bad_path(err, t, tn, "an array without dimensions");
            return 0;
        }
        for (d = 0U; d < ndims; d++) {
            int64_t lo = dims[d].lo;
            int64_t hi = dims[d].hi;
            uint64_t len = (hi < lo) ? 0U : (((uint64_t)hi - (uint64_t)lo) + 1U);
            uint64_t off = 0U;
            if ((size_t)d < take) {
                int64_t v = ix[left + d];
                if ((v < lo) || (v > hi)) {
                    sim_puts(err, "index ");
                    sim_put_i64(err, v);
                    sim_puts(err, " of `");
                    sim_put(err, t, tn);
                    sim_puts(err, "` is outside its bounds ");
                    sim_put_i64(err, lo);
                    sim_puts(err, "..");
                    sim_put_i64(err, hi);
                    return 0;
                }
                off = (uint64_t)v - (uint64_t)lo;
            }
            if (mul_add(&flat, len, off) == 0) {
                flat = UINT64_MAX;
            }
        }
        if ((flat == UINT64_MAX) || (mul_add(&flat, (uint64_t)stride, 0U) == 0) || (flat > (uint64_t)SIZE_MAX)) {
            sim_putc(err, '`');
            sim_put(err, t, tn);
            sim_puts(err, "` is outside the memory");
            return 0;
        }
        loc_add(p, (size_t)flat);
        if (take < (size_t)ndims) {
            p->view.slice = 1;
            p->view.type = elem;
            p->view.dims = &dims[take];
            p->view.ndims = ndims - (uint32_t)take;
            p->view.stride = stride;
        } else {
            p->view.slice = 0;
            p->view.type = elem;
            p->view.dims = NULL;
            p->view.ndims = 0U;
            p->view.stride = 0U;
        }
        left += take;
    }
    sim_putc(&p->name, '[');
    for (i = 0U; i < nix; i++) {
        if (i > 0U) {
            sim_putc(&p->name, ',');
        }
        sim_put_i64(&p->name, ix[i]);
    }
    sim_putc(&p->name, ']');
    return 1;
}

int sim_resolve(const sim_scope *sc, const char *text, size_t n, sim_place *out, sim_buf *err)
{
    sim_path p;
    const char *t = text;
    size_t tn = n;
    size_t i;
    int ok;
    sim_trim(&t, &tn);
    if (parse_path(text, n, &p, err) == 0) {
        return 0;
    }
    if (p.is_addr != 0) {
        ok = resolve_address(&p.addr, t, tn, out, err);
    } else {
        ok = resolve_root(sc, p.root, p.rlen, t, tn, out, err);
    }
    for (i = 0U; (ok != 0) && (i < p.nsegs); i++) {
        if (p.segs[i].is_index != 0) {
            ok = resolve_index(out, p.segs[i].idx, p.segs[i].nidx, t, tn, err);
        } else {
            ok = resolve_member(out, p.segs[i].name, p.segs[i].nlen, t, tn, err);
        }
        if (ok == 0) {
            sim_place_free(out);
        }
    }
    path_free(&p);
    return ok;
}

/* ---- watch lists ------------------------------------------------------------ */

size_t sim_split_list(const char *text, size_t n, char ***items)
{
    size_t depth = 0U;
    size_t start = 0U;
    size_t count = 0U;
    size_t i;
    char **out = NULL;
    for (i = 0U; i <= n; i++) {
        int split = 0;
        if (i == n) {
            split = 1;
        } else if (text[i] == '[') {
            depth++;
        } else if (text[i] == ']') {
            if (depth > 0U) {
                depth--;
            }
        } else if ((text[i] == ',') && (depth == 0U)) {
            split = 1;
        } else {
            /* part of an item */
        }
        if (split != 0) {
            const char *s = &text[start];
            size_t len = i - start;
            sim_trim(&s, &len);
            if (len > 0U) {
                out = (char **)sim_grow(out, count + 1U, sizeof(char *));
                out[count] = sim_strndup(s, len);
                count++;
            }
            start = i + 1U;
        }
    }
    *items = out;
    return count;
}

static void add_default(const sim_scope *sc, sim_place **out, size_t *count, const char *path, size_t n)
{
    sim_place p;
    sim_buf err;
    size_t i;
    sim_buf_init(&err);
    if (sim_resolve(sc, path, n, &p, &err) != 0) {
        for (i = 0U; i < *count; i++) {
            if (sim_ieq((*out)[i].name.p, (*out)[i].name.len, p.name.p, p.name.len) != 0) {
                break;
            }
        }
        if (i == *count) {
            *out = (sim_place *)sim_grow(*out, *count + 1U, sizeof(sim_place));
            (*out)[*count] = p;
            (*count)++;
        } else {
            sim_place_free(&p);
        }
    }
    sim_buf_free(&err);
}

static void add_member_path(const sim_scope *sc, sim_place **out, size_t *count, const stc_program *inst,
                            const stc_member *m)
{
    sim_buf path;
    sim_buf_init(&path);
    sim_puts(&path, inst->name);
    sim_putc(&path, '.');
    sim_puts(&path, m->name);
    add_default(sc, out, count, path.p, path.len);
    sim_buf_free(&path);
}

size_t sim_default_watch(const sim_scope *sc, sim_place **out)
{
    size_t count = 0U;
    size_t i;
    uint32_t k;
    *out = NULL;
    for (i = 0U; i < sc->ninst; i++) {
        const stc_type *d = sim_type(sc->inst[i]->type);
        if ((d == NULL) || (d->kind != (uint8_t)STC_TK_INSTANCE)) {
            continue;
        }
        for (k = 0U; k < d->count; k++) {
            if (d->members[k].kind == (uint8_t)STC_VK_OUTPUT) {
                add_member_path(sc, out, &count, sc->inst[i], &d->members[k]);
            }
        }
    }
    for (k = 0U; k < stc_n_globals; k++) {
        const stc_global *g = &stc_globals[k];
        int visible = (g->config < 0) || (g->config == sc->config);
        if ((visible != 0) && (sim_location_area(g->location) == 'Q')) {
            add_default(sc, out, &count, g->name, strlen(g->name));
        }
    }
    for (i = 0U; i < sc->ninst; i++) {
        const stc_type *d = sim_type(sc->inst[i]->type);
        if ((d == NULL) || (d->kind != (uint8_t)STC_TK_INSTANCE)) {
            continue;
        }
        for (k = 0U; k < d->count; k++) {
            if (sim_location_area(d->members[k].location) == 'Q') {
                add_member_path(sc, out, &count, sc->inst[i], &d->members[k]);
            }
        }
    }
    return count;
}

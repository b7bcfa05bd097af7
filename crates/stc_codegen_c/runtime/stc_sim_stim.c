/*
 * stc_sim_stim.c - stimulus files (a port of stc_runtime's stimulus.rs):
 * a header `cycle,PATH,PATH,...`, then rows that assign those variables
 * just before the row's cycle runs; an empty cell leaves a variable alone.
 * A single-quoted ST string literal is one cell even with commas inside;
 * RFC 4180 double quotes work too. Blank lines are skipped.
 */
#include "stc_sim.h"

#include <stdlib.h>
#include <string.h>

typedef struct {
    sim_text *cells;
    size_t n;
} sim_cells;

static void cells_free(sim_cells *c)
{
    size_t i;
    for (i = 0U; i < c->n; i++) {
        free(c->cells[i].p);
    }
    free(c->cells);
    c->cells = NULL;
    c->n = 0U;
}

static void cells_push(sim_cells *c, const char *s, size_t n, int trim)
{
    const char *p = s;
    size_t len = n;
    if (trim != 0) {
        sim_trim(&p, &len);
    }
    c->cells = (sim_text *)sim_grow(c->cells, c->n + 1U, sizeof(sim_text));
    c->cells[c->n].p = sim_strndup(p, len);
    c->cells[c->n].n = len;
    c->n++;
}

/* stimulus.rs split_record: one line into cells. */
static int split_record(const char *line, size_t n, sim_cells *out, sim_buf *err)
{
    size_t i = 0U;
    sim_buf cell;
    out->cells = NULL;
    out->n = 0U;
    sim_buf_init(&cell);
    for (;;) {
        sim_buf_clear(&cell);
        while ((i < n) && ((line[i] == ' ') || (line[i] == '\t'))) {
            i++;
        }
        if ((i < n) && (line[i] == '"')) {
            i++;
            for (;;) {
                if (i >= n) {
                    sim_puts(err, "a `\"` quoted cell is not closed");
                    sim_buf_free(&cell);
                    cells_free(out);
                    return 0;
                }
                if (line[i] == '"') {
                    if (((i + 1U) < n) && (line[i + 1U] == '"')) {
                        sim_putc(&cell, '"');
                        i += 2U;
                        continue;
                    }
                    i++;
                    break;
                }
                sim_putc(&cell, line[i]);
                i++;
            }
            while ((i < n) && ((line[i] == ' ') || (line[i] == '\t'))) {
                i++;
            }
            if (i >= n) {
                cells_push(out, cell.p, cell.len, 0);
                sim_buf_free(&cell);
                return 1;
            }
            if (line[i] == ',') {
                i++;
                cells_push(out, cell.p, cell.len, 0);
                continue;
            }
            {
                uint32_t cp;
                size_t len = sim_utf8_next(&line[i], n - i, &cp);
                sim_puts(err, "unexpected `");
                sim_put(err, &line[i], len);
                sim_puts(err, "` after a quoted cell");
            }
            sim_buf_free(&cell);
            cells_free(out);
            return 0;
        }
        for (;;) {
            if (i >= n) {
                cells_push(out, cell.p, cell.len, 1);
                sim_buf_free(&cell);
                return 1;
            }
            if (line[i] == ',') {
                i++;
                break;
            }
            if (line[i] == '\'') {
                sim_putc(&cell, '\'');
                i++;
                for (;;) {
                    if (i >= n) {
                        sim_puts(err, "a `'` string is not closed");
                        sim_buf_free(&cell);
                        cells_free(out);
                        return 0;
                    }
                    if (line[i] == '$') {
                        sim_putc(&cell, '$');
                        i++;
                        if (i < n) {
                            uint32_t cp;
                            size_t len = sim_utf8_next(&line[i], n - i, &cp);
                            sim_put(&cell, &line[i], len);
                            i += len;
                        }
                    } else if (line[i] == '\'') {
                        sim_putc(&cell, '\'');
                        i++;
                        break;
                    } else {
                        sim_putc(&cell, line[i]);
                        i++;
                    }
                }
            } else {
                sim_putc(&cell, line[i]);
                i++;
            }
        }
        cells_push(out, cell.p, cell.len, 1);
    }
}

void sim_stimulus_free(sim_stimulus *st)
{
    size_t i;
    size_t k;
    for (i = 0U; i < st->ncols; i++) {
        free(st->columns[i].p);
    }
    free(st->columns);
    for (i = 0U; i < st->nrows; i++) {
        for (k = 0U; k < st->ncols; k++) {
            free(st->rows[i].cells[k].p);
        }
        free(st->rows[i].cells);
    }
    free(st->rows);
    (void)memset(st, 0, sizeof *st);
    st->columns = NULL;
    st->rows = NULL;
}

static int is_blank(const char *s, size_t n)
{
    const char *p = s;
    size_t len = n;
    sim_trim(&p, &len);
    return (len == 0U) ? 1 : 0;
}

/* A cycle number: `_` removed, then Rust's u64 parse (an optional `+`),
   at least 1. */
static int parse_cycle(const char *s, size_t n, uint64_t *out)
{
    size_t i;
    size_t digits = 0U;
    int plus = 0;
    uint64_t v = 0U;
    if (n == 0U) {
        return 0;
    }
    for (i = 0U; i < n; i++) {
        char c = s[i];
        if (c == '_') {
            continue;
        }
        if ((digits == 0U) && (plus == 0) && (c == '+')) {
            plus = 1;
            continue;
        }
        if ((c < '0') || (c > '9')) {
            return 0;
        }
        if (v > ((UINT64_MAX - (uint64_t)(c - '0')) / 10U)) {
            return 0;
        }
        v = (v * 10U) + (uint64_t)(c - '0');
        digits++;
    }
    if ((digits == 0U) || (v < 1U)) {
        return 0;
    }
    *out = v;
    return 1;
}

int sim_stimulus_parse(const char *text, size_t n, sim_stimulus *st, size_t *line, sim_buf *err)
{
    size_t pos = 0U;
    size_t lineno = 0U;
    int have_header = 0;
    sim_cells cells;
    (void)memset(st, 0, sizeof *st);
    st->columns = NULL;
    st->rows = NULL;
    if ((n >= 3U) && ((unsigned char)text[0] == 0xEFU) && ((unsigned char)text[1] == 0xBBU) &&
        ((unsigned char)text[2] == 0xBFU)) {
        pos = 3U;
    }
    while (pos < n) {
        const char *nl = (const char *)memchr(&text[pos], '\n', n - pos);
        const char *l = &text[pos];
        size_t len;
        if (nl != NULL) {
            len = (size_t)(nl - l);
            pos += len + 1U;
            if ((len > 0U) && (l[len - 1U] == '\r')) {
                len--;
            }
        } else {
            len = n - pos;
            pos = n;
        }
        lineno++;
        if (is_blank(l, len) != 0) {
            continue;
        }
        *line = lineno;
        if (split_record(l, len, &cells, err) == 0) {
            sim_stimulus_free(st);
            return 0;
        }
        if (have_header == 0) {
            size_t i;
            have_header = 1;
            st->header_line = lineno;
            if (sim_ieq_z(cells.cells[0].p, cells.cells[0].n, "cycle") == 0) {
                sim_puts(err, "the header must start with `cycle`, not `");
                sim_put(err, cells.cells[0].p, cells.cells[0].n);
                sim_putc(err, '`');
                cells_free(&cells);
                sim_stimulus_free(st);
                return 0;
            }
            for (i = 1U; i < cells.n; i++) {
                if (cells.cells[i].n == 0U) {
                    sim_puts(err, "column ");
                    sim_put_u64(err, (uint64_t)i + 1U);
                    sim_puts(err, " of the header has no variable path");
                    cells_free(&cells);
                    sim_stimulus_free(st);
                    return 0;
                }
            }
            st->ncols = cells.n - 1U;
            st->columns = (sim_text *)sim_alloc((st->ncols + 1U) * sizeof(sim_text));
            for (i = 1U; i < cells.n; i++) {
                st->columns[i - 1U] = cells.cells[i];
                cells.cells[i].p = NULL;
            }
            cells_free(&cells);
        } else {
            sim_row *r;
            size_t i;
            uint64_t cycle;
            if (cells.n > (st->ncols + 1U)) {
                sim_puts(err, "this row has ");
                sim_put_u64(err, (uint64_t)cells.n);
                sim_puts(err, " cells but the header has ");
                sim_put_u64(err, (uint64_t)st->ncols + 1U);
                sim_puts(err, " columns");
                cells_free(&cells);
                sim_stimulus_free(st);
                return 0;
            }
            if (parse_cycle(cells.cells[0].p, cells.cells[0].n, &cycle) == 0) {
                sim_putc(err, '`');
                sim_put(err, cells.cells[0].p, cells.cells[0].n);
                sim_puts(err, "` is not a cycle number (1, 2, ...)");
                cells_free(&cells);
                sim_stimulus_free(st);
                return 0;
            }
            /* Insert after every row of the same or an earlier cycle: rows
               apply in cycle order, rows of one cycle in file order. */
            st->rows = (sim_row *)sim_grow(st->rows, st->nrows + 1U, sizeof(sim_row));
            i = st->nrows;
            while ((i > 0U) && (st->rows[i - 1U].cycle > cycle)) {
                st->rows[i] = st->rows[i - 1U];
                i--;
            }
            r = &st->rows[i];
            st->nrows++;
            r->line = lineno;
            r->cycle = cycle;
            r->cells = (sim_text *)sim_alloc((st->ncols + 1U) * sizeof(sim_text));
            for (i = 0U; i < st->ncols; i++) {
                if (((i + 1U) < cells.n) && (cells.cells[i + 1U].n > 0U)) {
                    r->cells[i] = cells.cells[i + 1U];
                    cells.cells[i + 1U].p = NULL;
                } else {
                    r->cells[i].p = NULL;
                    r->cells[i].n = 0U;
                }
            }
            cells_free(&cells);
        }
    }
    if (have_header == 0) {
        *line = 1U;
        sim_puts(err, "the file is empty: expected a header `cycle,PATH,...`");
        return 0;
    }
    return 1;
}

//! Stimulus files (`--stimulus FILE.csv`, spec/cli.md): a header
//! `cycle,PATH,PATH,...`, then rows that assign those variables just before
//! the row's cycle runs; an empty cell leaves a variable alone. With the
//! header `time,PATH,...` a row gives the time of its cycle instead
//! (`T#1s` or `1s`: the cycle that runs at that time, so the file keeps its
//! meaning when `--tick` changes; a time between two cycles is an error).
//!
//! The cells are ST literals, so the reader is not plain RFC 4180: a
//! single-quoted STRING literal (`'a,b'`, with `$'` escapes) is one cell
//! even when it holds commas. RFC 4180 double quotes work too (`"a,b"`,
//! `""` for a quote inside). A row is one line; blank lines are skipped.
//! This module only reads the text; paths and values are checked against
//! the program when a simulation is set up.

use crate::error::{Error, Result};

/// A stimulus file, read but not yet resolved.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Stimulus {
    /// The file name, for messages.
    pub file: String,
    /// The paths of the header, after `cycle`.
    pub columns: Vec<String>,
    /// 1-based line of the header.
    pub header_line: usize,
    pub rows: Vec<Row>,
}

/// When a row applies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum At {
    /// Before cycle k (1-based) runs.
    Cycle(u64),
    /// Before the cycle that runs at this time (nanoseconds) runs.
    Time(i64),
}

impl At {
    /// The cycle (1-based) with a tick of `tick_ns`; `None` for a time
    /// that is not a cycle's.
    pub fn cycle(self, tick_ns: i64) -> Option<u64> {
        match self {
            At::Cycle(c) => Some(c),
            At::Time(t) if tick_ns > 0 && t % tick_ns == 0 => {
                u64::try_from(t / tick_ns).ok()?.checked_add(1)
            }
            At::Time(_) => None,
        }
    }
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Row {
    /// 1-based line in the file.
    pub line: usize,
    pub at: At,
    /// One cell per column; `None` leaves the variable alone.
    pub cells: Vec<Option<String>>,
}

impl Stimulus {
    pub fn parse(file: &str, text: &str) -> Result<Stimulus> {
        let err = |line: usize, message: String| Error::Stimulus {
            file: file.to_string(),
            line,
            message,
        };
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l))
            .filter(|(_, l)| !l.trim().is_empty());
        let Some((header_line, header)) = lines.next() else {
            return Err(err(
                1,
                "the file is empty: expected a header `cycle,PATH,...`".into(),
            ));
        };
        let names = split_record(header).map_err(|m| err(header_line, m))?;
        let first = names.first().map(|s| s.as_str()).unwrap_or("");
        let timed = first.eq_ignore_ascii_case("time");
        if !first.eq_ignore_ascii_case("cycle") && !timed {
            return Err(err(
                header_line,
                format!("the header must start with `cycle` or `time`, not `{first}`"),
            ));
        }
        let columns: Vec<String> = names[1..].to_vec();
        if let Some(i) = columns.iter().position(|c| c.is_empty()) {
            return Err(err(
                header_line,
                format!("column {} of the header has no variable path", i + 2),
            ));
        }
        let mut rows = Vec::new();
        for (line, text) in lines {
            let cells = split_record(text).map_err(|m| err(line, m))?;
            if cells.len() > columns.len() + 1 {
                return Err(err(
                    line,
                    format!(
                        "this row has {} cells but the header has {} columns",
                        cells.len(),
                        columns.len() + 1
                    ),
                ));
            }
            let c = cells[0].as_str();
            let at = if timed {
                let t = crate::parse_tick(c)
                    .ok()
                    .or_else(|| {
                        (c.trim() == "0" || c.trim().eq_ignore_ascii_case("T#0s")).then_some(0)
                    })
                    .ok_or_else(|| {
                        err(line, format!("`{c}` is not a time (T#0s, T#100ms, 1s...)"))
                    })?;
                At::Time(t)
            } else {
                At::Cycle(
                    c.replace('_', "")
                        .parse::<u64>()
                        .ok()
                        .filter(|&n| n >= 1 && !c.is_empty())
                        .ok_or_else(|| {
                            err(line, format!("`{c}` is not a cycle number (1, 2, ...)"))
                        })?,
                )
            };
            let mut values: Vec<Option<String>> = cells[1..]
                .iter()
                .map(|s| (!s.is_empty()).then(|| s.clone()))
                .collect();
            values.resize(columns.len(), None);
            rows.push(Row {
                line,
                at,
                cells: values,
            });
        }
        // Rows apply in cycle order; rows of one cycle in file order.
        rows.sort_by_key(|r| r.at);
        Ok(Stimulus {
            file: file.to_string(),
            columns,
            header_line,
            rows,
        })
    }
}

/// Splits one line into trimmed cells (see the module comment).
pub fn split_record(line: &str) -> std::result::Result<Vec<String>, String> {
    let mut cells = Vec::new();
    let mut chars = line.chars().peekable();
    loop {
        let mut cell = String::new();
        while chars.peek().is_some_and(|c| *c == ' ' || *c == '\t') {
            chars.next();
        }
        if chars.peek() == Some(&'"') {
            chars.next();
            loop {
                match chars.next() {
                    Some('"') if chars.peek() == Some(&'"') => {
                        chars.next();
                        cell.push('"');
                    }
                    Some('"') => break,
                    Some(c) => cell.push(c),
                    None => return Err("a `\"` quoted cell is not closed".into()),
                }
            }
            while chars.peek().is_some_and(|c| *c == ' ' || *c == '\t') {
                chars.next();
            }
            match chars.next() {
                None => {
                    cells.push(cell);
                    return Ok(cells);
                }
                Some(',') => {
                    cells.push(cell);
                    continue;
                }
                Some(c) => return Err(format!("unexpected `{c}` after a quoted cell")),
            }
        }
        loop {
            match chars.next() {
                None => {
                    cells.push(cell.trim().to_string());
                    return Ok(cells);
                }
                Some(',') => break,
                Some('\'') => {
                    cell.push('\'');
                    loop {
                        match chars.next() {
                            Some('$') => {
                                cell.push('$');
                                if let Some(c) = chars.next() {
                                    cell.push(c);
                                }
                            }
                            Some('\'') => {
                                cell.push('\'');
                                break;
                            }
                            Some(c) => cell.push(c),
                            None => return Err("a `'` string is not closed".into()),
                        }
                    }
                }
                Some(c) => cell.push(c),
            }
        }
        cells.push(cell.trim().to_string());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cells(line: &str) -> Vec<String> {
        split_record(line).unwrap()
    }

    #[test]
    fn cells_are_trimmed_and_quotes_keep_commas() {
        assert_eq!(cells("1, TRUE ,,x"), ["1", "TRUE", "", "x"]);
        assert_eq!(cells("2,'a,b',c"), ["2", "'a,b'", "c"]);
        assert_eq!(cells("2,'it$'s, ok',c"), ["2", "'it$'s, ok'", "c"]);
        assert_eq!(cells("3,\"x,\"\"y\"\"\" , z"), ["3", "x,\"y\"", "z"]);
        assert_eq!(cells("4,\"'q,r'\""), ["4", "'q,r'"]);
        assert_eq!(cells(""), [""]);
        assert_eq!(cells("5,"), ["5", ""]);
        assert_eq!(
            split_record("1,'abc"),
            Err("a `'` string is not closed".into())
        );
        assert_eq!(
            split_record("1,\"abc"),
            Err("a `\"` quoted cell is not closed".into())
        );
        assert_eq!(
            split_record("1,\"a\"b"),
            Err("unexpected `b` after a quoted cell".into())
        );
    }

    #[test]
    fn a_stimulus_file_has_a_header_and_rows_sorted_by_cycle() {
        let st = Stimulus::parse(
            "s.csv",
            "\u{feff}cycle,Main.a,g\r\n\r\n3,5,\r\n1,TRUE,'x'\r\n1,,7\n2\n",
        )
        .unwrap();
        assert_eq!(st.columns, ["Main.a", "g"]);
        assert_eq!(st.header_line, 1);
        let rows: Vec<(usize, u64, Vec<Option<&str>>)> = st
            .rows
            .iter()
            .map(|r| {
                (
                    r.line,
                    r.at.cycle(1).unwrap(),
                    r.cells.iter().map(|c| c.as_deref()).collect(),
                )
            })
            .collect();
        assert_eq!(
            rows,
            [
                (4, 1, vec![Some("TRUE"), Some("'x'")]),
                (5, 1, vec![None, Some("7")]),
                (6, 2, vec![None, None]),
                (3, 3, vec![Some("5"), None]),
            ]
        );
    }

    #[test]
    fn timed_rows_apply_at_the_cycle_of_their_time() {
        let st = Stimulus::parse("s.csv", "time,g\nT#20ms,2\n0,1\n1s,9\n").unwrap();
        let at: Vec<At> = st.rows.iter().map(|r| r.at).collect();
        let ms = 1_000_000;
        assert_eq!(at, [At::Time(0), At::Time(20 * ms), At::Time(1000 * ms)]);
        assert_eq!(at[1].cycle(10 * ms), Some(3));
        assert_eq!(at[1].cycle(5 * ms), Some(5));
        assert_eq!(at[1].cycle(15 * ms), None);
        assert_eq!(at[0].cycle(10 * ms), Some(1));
    }

    #[test]
    fn malformed_stimulus_files_name_the_line() {
        let e = |text: &str| Stimulus::parse("s.csv", text).unwrap_err().to_string();
        assert_eq!(
            e(""),
            "s.csv:1: the file is empty: expected a header `cycle,PATH,...`"
        );
        assert_eq!(
            e("\n\nstep,x\n"),
            "s.csv:3: the header must start with `cycle` or `time`, not `step`"
        );
        assert_eq!(
            e("time,x\nlater,1\n"),
            "s.csv:2: `later` is not a time (T#0s, T#100ms, 1s...)"
        );
        assert_eq!(
            e("cycle,x,,y\n"),
            "s.csv:1: column 3 of the header has no variable path"
        );
        assert_eq!(
            e("Cycle,x\n1,2,3\n"),
            "s.csv:2: this row has 3 cells but the header has 2 columns"
        );
        assert_eq!(
            e("cycle,x\n0,1\n"),
            "s.csv:2: `0` is not a cycle number (1, 2, ...)"
        );
        assert_eq!(
            e("cycle,x\n-1,1\n"),
            "s.csv:2: `-1` is not a cycle number (1, 2, ...)"
        );
        assert_eq!(
            e("cycle,x\n,1\n"),
            "s.csv:2: `` is not a cycle number (1, 2, ...)"
        );
        assert_eq!(e("cycle,x\n1,'a\n"), "s.csv:2: a `'` string is not closed");
    }
}

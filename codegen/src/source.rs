//! Model source text before tokens: reading a file as bytes (a byte that is
//! not UTF-8 is located at its line and column), the byte order mark, and
//! delimiters that do not balance (the tokenizer's own error has no place).
//!
//! Lines and columns are those of the tokenizer: lines split at `\n` (a
//! `\r\n` line end is one line end), columns count characters from 1, a tab
//! being one column.

use crate::diagnostic::Diagnostics;

/// The text of a model file: UTF-8 without its byte order mark, or the
/// report of the first byte that is not UTF-8.
///
/// On failure: the error, located, and the text with the bad bytes replaced
/// (for showing the line).
pub fn decode(bytes: &[u8]) -> Result<String, (Diagnostics, String)> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    match std::str::from_utf8(bytes) {
        Ok(s) => Ok(s.to_string()),
        Err(e) => {
            let good = &bytes[..e.valid_up_to()];
            let text = String::from_utf8_lossy(bytes);
            let line = good.iter().filter(|&&b| b == b'\n').count() + 1;
            let line_start = good.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
            let col = String::from_utf8_lossy(&good[line_start..]).chars().count() + 1;
            let mut d = Diagnostics::new();
            d.error_at(
                line,
                col,
                format!(
                    "the file is not valid UTF-8 at byte 0x{:02X} (save it as UTF-8)",
                    bytes[e.valid_up_to()]
                ),
            );
            Err((d, text.into_owned()))
        }
    }
}

/// `source` without a leading byte order mark (editors do not show it, so
/// columns are counted without it).
pub fn strip_bom(source: &str) -> &str {
    source.strip_prefix('\u{feff}').unwrap_or(source)
}

/// A delimiter found by [`unbalanced`].
#[derive(Clone, Copy, Debug)]
struct Delim {
    ch: char,
    line: usize,
    col: usize,
    indent: usize,
}

fn closing(open: char) -> char {
    match open {
        '(' => ')',
        '[' => ']',
        _ => '}',
    }
}

/// Find why the delimiters of `source` do not balance, as a located error:
/// a block comment or a string never closed (at where it starts: it
/// swallows every delimiter after it, as rustc reports it), a closer with
/// nothing open, a closer of the wrong kind, or an opener that is never
/// closed. For the last, the opener reported is the one whose
/// closer is indented unlike its own line but like the unclosed outer
/// opener's (the usual forgotten `}`); else the unclosed opener itself.
/// Strings, character literals and comments are skipped.
pub fn unbalanced(source: &str, diags: &mut Diagnostics) -> bool {
    let indents: Vec<usize> = source
        .lines()
        .map(|l| l.chars().take_while(|c| c.is_whitespace()).count())
        .collect();
    let indent = |line: usize| indents.get(line - 1).copied().unwrap_or(0);
    let chars: Vec<char> = source.chars().collect();
    let (mut line, mut col) = (1usize, 1usize);
    let mut stack: Vec<Delim> = Vec::new();
    let mut matched: Vec<(Delim, Delim)> = Vec::new();
    let mut i = 0;
    // Advance over chars[i], keeping line and column.
    let step = |i: &mut usize, line: &mut usize, col: &mut usize| {
        if chars[*i] == '\n' {
            *line += 1;
            *col = 1;
        } else {
            *col += 1;
        }
        *i += 1;
    };
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        match c {
            '/' if next == Some('/') => {
                while i < chars.len() && chars[i] != '\n' {
                    step(&mut i, &mut line, &mut col);
                }
                continue;
            }
            '/' if next == Some('*') => {
                let (start_line, start_col) = (line, col);
                let mut depth = 0;
                while i < chars.len() {
                    if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                        depth += 1;
                        step(&mut i, &mut line, &mut col);
                    } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                        depth -= 1;
                        step(&mut i, &mut line, &mut col);
                        if depth == 0 {
                            step(&mut i, &mut line, &mut col);
                            break;
                        }
                    }
                    step(&mut i, &mut line, &mut col);
                }
                if depth > 0 {
                    diags.error_at(
                        start_line,
                        start_col,
                        "unterminated block comment: this `/*` is never closed by a `*/` \
                         (block comments nest: every `/*` inside needs its own `*/`)",
                    );
                    return true;
                }
                continue;
            }
            '"' => {
                let (start_line, start_col) = (line, col);
                step(&mut i, &mut line, &mut col);
                while i < chars.len() && chars[i] != '"' {
                    if chars[i] == '\\' {
                        step(&mut i, &mut line, &mut col);
                    }
                    if i < chars.len() {
                        step(&mut i, &mut line, &mut col);
                    }
                }
                if i >= chars.len() {
                    diags.error_at(
                        start_line,
                        start_col,
                        "unterminated string: this `\"` is never closed by another `\"`",
                    );
                    return true;
                }
            }
            '\'' if chars.get(i + 2) == Some(&'\'') => {
                step(&mut i, &mut line, &mut col);
                step(&mut i, &mut line, &mut col);
            }
            '(' | '[' | '{' => stack.push(Delim {
                ch: c,
                line,
                col,
                indent: indent(line),
            }),
            ')' | ']' | '}' => {
                let here = Delim {
                    ch: c,
                    line,
                    col,
                    indent: indent(line),
                };
                match stack.pop() {
                    None => {
                        diags.error_at(
                            line,
                            col,
                            format!("unexpected closing `{c}`: nothing is open here"),
                        );
                        return true;
                    }
                    Some(open) if closing(open.ch) != c => {
                        diags.error_at(
                            line,
                            col,
                            format!(
                                "mismatched closing `{c}`: the `{}` at {}:{} is still open",
                                open.ch, open.line, open.col
                            ),
                        );
                        return true;
                    }
                    Some(open) => matched.push((open, here)),
                }
            }
            _ => {}
        }
        if i < chars.len() {
            step(&mut i, &mut line, &mut col);
        }
    }
    let Some(&outer) = stack.last() else {
        return false;
    };
    let suspect = matched.iter().rev().find(|(o, c)| {
        (o.line, o.col) > (outer.line, outer.col)
            && c.line != o.line
            && c.indent != o.indent
            && c.indent == outer.indent
    });
    match suspect {
        Some((o, c)) => diags.error_at(
            o.line,
            o.col,
            format!(
                "this `{}` is never closed (the `{}` on line {} seems to belong to the `{}` on line {})",
                o.ch, c.ch, c.line, outer.ch, outer.line
            ),
        ),
        None => diags.error_at(
            outer.line,
            outer.col,
            format!("this `{}` is never closed", outer.ch),
        ),
    }
    true
}

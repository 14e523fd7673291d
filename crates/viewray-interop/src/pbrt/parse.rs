//! pbrt-v4's scene-file syntax: tokens with their line and column, and the
//! `"type name" value` parameter lists that follow a directive.

use std::path::Path;

use crate::ImportError;

/// A token of a pbrt file.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Token<'a> {
    Word(&'a str),
    Text(&'a str),
    Number(f64),
    Open,
    Close,
}

/// A token and its 1-based line and column.
pub(super) type Located<'a> = (Token<'a>, (usize, usize));

/// The tokenizer: the text and where it has read to.
struct Tokens<'a> {
    text: &'a str,
    offset: usize,
    line: usize,
    line_start: usize,
}

impl<'a> Tokens<'a> {
    fn position(&self) -> (usize, usize) {
        let column = self.text[self.line_start..self.offset.min(self.text.len())]
            .chars()
            .count()
            + 1;
        (self.line, column)
    }

    /// The next token and where it starts; `None` at the end.
    fn next(&mut self, path: &Path) -> Result<Option<Located<'a>>, ImportError> {
        let bytes = self.text.as_bytes();
        loop {
            match bytes.get(self.offset) {
                None => return Ok(None),
                Some(b'\n') => {
                    self.offset += 1;
                    self.line += 1;
                    self.line_start = self.offset;
                }
                Some(b' ' | b'\t' | b'\r') => self.offset += 1,
                Some(b'#') => {
                    while let Some(&b) = bytes.get(self.offset) {
                        if b == b'\n' {
                            break;
                        }
                        self.offset += 1;
                    }
                }
                Some(_) => break,
            }
        }
        let at = self.position();
        let start = self.offset;
        let token = match bytes[start] {
            b'[' => {
                self.offset += 1;
                Token::Open
            }
            b']' => {
                self.offset += 1;
                Token::Close
            }
            b'"' => {
                let end = self.text[start + 1..]
                    .find(['"', '\n'])
                    .map(|i| start + 1 + i)
                    .filter(|&i| bytes[i] == b'"')
                    .ok_or_else(|| ImportError::new(path, Some(at), "unterminated string"))?;
                self.offset = end + 1;
                Token::Text(&self.text[start + 1..end])
            }
            _ => {
                let end = self.text[start..]
                    .find(|c: char| c.is_whitespace() || matches!(c, '[' | ']' | '"' | '#'))
                    .map_or(self.text.len(), |i| start + i);
                self.offset = end;
                let word = &self.text[start..end];
                match word.parse::<f64>() {
                    Ok(x) if x.is_finite() => Token::Number(x),
                    Ok(_) => {
                        return Err(ImportError::new(
                            path,
                            Some(at),
                            format!("`{word}` is not a finite number"),
                        ));
                    }
                    Err(_) if word.chars().next().is_some_and(|c| c.is_ascii_alphabetic()) => {
                        Token::Word(word)
                    }
                    Err(_) => {
                        return Err(ImportError::new(
                            path,
                            Some(at),
                            format!(
                                "unexpected `{word}`, expected a directive, a string, a number or [ ]"
                            ),
                        ));
                    }
                }
            }
        };
        Ok(Some((token, at)))
    }
}

/// A parameter's values.
#[derive(Clone, Debug)]
enum Values {
    Numbers(Vec<f64>),
    Strings(Vec<String>),
}

/// `"type name" value` parameters of a directive.
#[derive(Default)]
pub(super) struct Params {
    list: Vec<(String, String, Values, (usize, usize))>,
}

impl Params {
    /// The numbers of the parameter `name` and where they start.
    pub(super) fn numbers(&self, name: &str) -> Option<(&[f64], (usize, usize))> {
        self.list.iter().find_map(|(_, n, v, at)| match v {
            Values::Numbers(x) if n == name => Some((x.as_slice(), *at)),
            _ => None,
        })
    }

    /// The first number of the parameter `name`.
    pub(super) fn number(&self, name: &str) -> Option<f64> {
        self.numbers(name).and_then(|(x, _)| x.first().copied())
    }

    /// The first string of the parameter `name`.
    pub(super) fn string(&self, name: &str) -> Option<&str> {
        self.list.iter().find_map(|(_, n, v, _)| match v {
            Values::Strings(s) if n == name => s.first().map(String::as_str),
            _ => None,
        })
    }
}

/// The tokens of a file, with one token of look-ahead.
pub(super) struct Parser<'a> {
    tokens: Tokens<'a>,
    peeked: Option<Located<'a>>,
    path: &'a Path,
}

impl<'a> Parser<'a> {
    /// A parser at the start of `text`; `path` names the file in errors.
    pub(super) fn new(text: &'a str, path: &'a Path) -> Self {
        Self {
            tokens: Tokens {
                text,
                offset: 0,
                line: 1,
                line_start: 0,
            },
            peeked: None,
            path,
        }
    }

    /// The next token, without taking it.
    pub(super) fn peek(&mut self) -> Result<Option<&Located<'a>>, ImportError> {
        if self.peeked.is_none() {
            self.peeked = self.tokens.next(self.path)?;
        }
        Ok(self.peeked.as_ref())
    }

    /// The next token and where it starts; `None` at the end.
    pub(super) fn next(&mut self) -> Result<Option<Located<'a>>, ImportError> {
        match self.peeked.take() {
            Some(t) => Ok(Some(t)),
            None => self.tokens.next(self.path),
        }
    }

    /// An error of the file at `at`.
    pub(super) fn error(&self, at: (usize, usize), message: impl Into<String>) -> ImportError {
        ImportError::new(self.path, Some(at), message)
    }

    /// `n` numbers, bare or in brackets.
    pub(super) fn numbers(
        &mut self,
        n: usize,
        directive: &str,
        at: (usize, usize),
    ) -> Result<Vec<f64>, ImportError> {
        let bracketed = matches!(self.peek()?, Some((Token::Open, _)));
        if bracketed {
            self.next()?;
        }
        let mut out = Vec::with_capacity(n);
        for _ in 0..n {
            match self.next()? {
                Some((Token::Number(x), _)) => out.push(x),
                Some((_, at)) => {
                    return Err(self.error(at, format!("{directive} takes {n} numbers")));
                }
                None => {
                    return Err(
                        self.error(at, format!("{directive} takes {n} numbers, the file ends"))
                    );
                }
            }
        }
        if bracketed {
            match self.next()? {
                Some((Token::Close, _)) => {}
                Some((_, at)) => {
                    return Err(self.error(at, format!("expected ] after {n} numbers")));
                }
                None => return Err(self.error(at, "expected ], the file ends")),
            }
        }
        Ok(out)
    }

    /// A directive's quoted type (`Shape "sphere"`).
    pub(super) fn kind(
        &mut self,
        directive: &str,
        at: (usize, usize),
    ) -> Result<String, ImportError> {
        let at = match self.next()? {
            Some((Token::Text(s), _)) => return Ok(s.to_owned()),
            Some((_, at)) => at,
            None => at,
        };
        Err(self.error(
            at,
            format!("{directive} needs a quoted name, e.g. {directive} \"name\""),
        ))
    }

    /// The `"type name" value` parameters that follow a directive.
    pub(super) fn params(&mut self) -> Result<Params, ImportError> {
        let mut params = Params::default();
        while let Some((Token::Text(_), _)) = self.peek()? {
            let Some((Token::Text(decl), at)) = self.next()? else {
                unreachable!("peeked a string")
            };
            let mut words = decl.split_whitespace();
            let (Some(ty), Some(name), None) = (words.next(), words.next(), words.next()) else {
                return Err(self.error(
                    at,
                    format!("expected a parameter \"type name\", found \"{decl}\""),
                ));
            };
            let (ty, name) = (ty.to_owned(), name.to_owned());
            let mut numbers = Vec::new();
            let mut strings = Vec::new();
            let mut one = |token: Token<'_>, at| -> Result<(), ImportError> {
                match token {
                    Token::Number(x) => numbers.push(x),
                    Token::Text(s) => strings.push(s.to_owned()),
                    Token::Word(w @ ("true" | "false")) => strings.push(w.to_owned()),
                    _ => {
                        return Err(ImportError::new(
                            self.path,
                            Some(at),
                            format!("parameter \"{decl}\" needs a value"),
                        ));
                    }
                }
                Ok(())
            };
            match self.next()? {
                Some((Token::Open, _)) => loop {
                    match self.next()? {
                        Some((Token::Close, _)) => break,
                        Some((token, at)) => one(token, at)?,
                        None => {
                            return Err(ImportError::new(
                                self.path,
                                Some(at),
                                format!("parameter \"{decl}\": expected ], the file ends"),
                            ));
                        }
                    }
                },
                Some((token, at)) => one(token, at)?,
                None => return Err(self.error(at, format!("parameter \"{decl}\" needs a value"))),
            }
            let values = if strings.is_empty() {
                Values::Numbers(numbers)
            } else if numbers.is_empty() {
                Values::Strings(strings)
            } else {
                return Err(self.error(
                    at,
                    format!("parameter \"{decl}\" mixes numbers and strings"),
                ));
            };
            params.list.push((ty, name, values, at));
        }
        Ok(params)
    }
}

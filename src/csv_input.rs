//! Reading CSV files of numbers (`depo fit`'s samples, a room's size classes): a header
//! naming the columns, `#` comments, fields trimmed; every error one line naming the file
//! and, for a row, its line (`data.csv line 3: ...`).

use std::fs::File;
use std::path::Path;

use csv::StringRecord;

/// One line of what went wrong.
type Error = String;

/// An open CSV file and its header.
pub struct CsvInput {
    name: String,
    reader: csv::Reader<File>,
    headers: StringRecord,
}

impl CsvInput {
    pub fn open(path: &Path) -> Result<Self, Error> {
        let name = path.display().to_string();
        let mut reader = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .comment(Some(b'#'))
            .from_path(path)
            .map_err(|e| format!("{name}: {e}"))?;
        let headers = reader.headers().map_err(|e| format!("{name}: {e}"))?.clone();
        Ok(Self { name, reader, headers })
    }

    /// The file's name as errors give it.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The index of the column named `wanted` (in any case).
    pub fn column(&self, wanted: &str) -> Option<usize> {
        self.headers.iter().position(|h| h.eq_ignore_ascii_case(wanted))
    }

    /// An error about the header: `message (found: a, b, c)`.
    pub fn header_error(&self, message: &str) -> Error {
        format!("{}: {message} (found: {})", self.name, self.headers.iter().collect::<Vec<_>>().join(", "))
    }

    /// The rows, in order.
    pub fn rows(&mut self) -> Result<Vec<CsvRow>, Error> {
        let name = &self.name;
        self.reader
            .records()
            .map(|record| {
                let record = record.map_err(|e| format!("{name}: {e}"))?;
                let line = record.position().map_or(0, |p| p.line());
                Ok(CsvRow { name: name.clone(), line, record })
            })
            .collect()
    }
}

/// One row of a [`CsvInput`].
pub struct CsvRow {
    name: String,
    /// Its line in the file.
    pub line: u64,
    record: StringRecord,
}

impl CsvRow {
    /// The finite number in column `index`, named `what` in the error.
    pub fn number(&self, index: usize, what: &str) -> Result<f64, Error> {
        let text = self.record.get(index).unwrap_or("");
        text.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| self.error(&format!("`{what}` '{text}' is not a finite number")))
    }

    /// An error about this row: `file line N: message`.
    pub fn error(&self, message: &str) -> Error {
        at_line(&self.name, self.line, message)
    }
}

/// An error about line `line` of the file `name`.
pub fn at_line(name: &str, line: u64, message: &str) -> Error {
    format!("{name} line {line}: {message}")
}

//! Numbers in text, and the memory check, shared by the studies' reports, the scene reader and
//! the command.

/// One line of what went wrong.
type Error = String;

/// A computed `x` in text (tables, notes, errors): to six significant digits, plainly where
/// that is short (`0.001`, not `0.0009999999999998899`; `3000`, not `3000.0000000000005`),
/// else in e-notation (`1.23457e-7`, `1e100`). JSON and CSV keep every digit.
pub fn shown(x: f64) -> String {
    if !x.is_finite() {
        return x.to_string();
    }
    let rounded: f64 = format!("{x:.5e}").parse().unwrap_or(x);
    let plain = rounded.to_string();
    if plain.len() <= 10 {
        plain
    } else {
        format!("{rounded:e}")
    }
}

/// Fails with one line when `items` of about `bytes_each` bytes would not fit in this
/// machine's memory (`MemTotal` of /proc/meminfo, or the address space where that is not
/// readable), instead of a capacity-overflow panic or an allocation-failure abort later.
pub fn check_memory(what: &str, items: u64, bytes_each: u64) -> Result<(), Error> {
    let limit = physical_memory().unwrap_or(isize::MAX as u64).min(isize::MAX as u64);
    match items.checked_mul(bytes_each) {
        Some(need) if need <= limit => Ok(()),
        need => Err(format!(
            "{what} needs {} of memory, more than this machine's {}",
            need.map_or_else(|| "more than 2^64 bytes".to_string(), gigabytes),
            gigabytes(limit)
        )),
    }
}

fn gigabytes(bytes: u64) -> String {
    format!("{:.1} GB", bytes as f64 / 1e9)
}

/// Total physical memory in bytes, where the system says.
fn physical_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

#[cfg(test)]
mod tests {
    use super::shown;

    #[test]
    fn computed_numbers_read_to_six_digits() {
        assert_eq!(shown(0.0009999999999998899), "0.001");
        assert_eq!(shown(3000.0000000000005), "3000");
        assert_eq!(shown(0.030000000000000002), "0.03");
        assert_eq!(shown(-0.014623553139192037), "-0.0146236");
        assert_eq!(shown(1.234567e-7), "1.23457e-7");
        assert_eq!(shown(1e300), "1e300");
        assert_eq!(shown(12.5), "12.5");
        assert_eq!(shown(0.0), "0");
        assert_eq!(shown(f64::INFINITY), "inf");
    }
}

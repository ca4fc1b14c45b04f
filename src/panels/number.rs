//! How the number fields read typed text: a decimal comma is accepted as a decimal point
//! (`0,9` is 0.9), as many shops write it; spaces are ignored and the long minus sign (−) is a
//! minus. Text with both a comma and a point, or more than one comma (`1,000.5`, `1,2,3`), is
//! not a number: the field keeps its value.

/// The number in `text` (the rules of the module), or `None`.
pub fn parse(text: &str) -> Option<f64> {
    let text: String = text.chars().filter(|c| !c.is_whitespace()).map(|c| if c == '−' { '-' } else { c }).collect();
    let commas = text.matches(',').count();
    let text = match commas {
        0 => text,
        1 if !text.contains('.') => text.replace(',', "."),
        _ => return None,
    };
    text.parse::<f64>().ok().filter(|x| x.is_finite())
}

#[cfg(test)]
mod tests {
    use super::parse;

    #[test]
    fn a_decimal_comma_reads_as_a_point_and_ambiguous_text_is_refused() {
        assert_eq!(parse("0,9"), Some(0.9));
        assert_eq!(parse(" 12,5 "), Some(12.5));
        assert_eq!(parse("0.9"), Some(0.9));
        assert_eq!(parse("−1,5"), Some(-1.5));
        assert_eq!(parse("1 000"), Some(1000.0), "spaces ignored");
        assert_eq!(parse("1,000.5"), None, "comma and point");
        assert_eq!(parse("1,2,3"), None, "two commas");
        assert_eq!(parse("abc"), None);
        assert_eq!(parse("inf"), None, "not finite");
    }
}

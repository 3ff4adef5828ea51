//! C99 hexadecimal floating-point numbers in OBJ vertex lines (`0x1.8p+1`,
//! as `printf("%a")` writes them; manifold's test meshes use them).
//!
//! Each such number is read exactly (correctly rounded to `f64` when it has
//! more digits than `f64` holds, which `%a` of a double never does) and
//! rewritten as the shortest decimal that reads back to the same bits, so
//! that the rest of the reader sees decimal numbers only. Tokens change
//! within their line: line numbers and the other bytes stay as they were.

use std::borrow::Cow;

/// `bytes` with every hexadecimal float of a vertex line (`v`, `vt`, `vn`,
/// `vp`) rewritten as decimal; borrowed when there is none. A token that
/// starts like a hexadecimal float but is not one is left alone, for the
/// reader to refuse with its line.
pub(super) fn decimal_floats(bytes: &[u8]) -> Cow<'_, [u8]> {
    if memchr::memmem::find(bytes, b"0x").is_none() && memchr::memmem::find(bytes, b"0X").is_none()
    {
        return Cow::Borrowed(bytes);
    }
    let mut out = Vec::with_capacity(bytes.len());
    let mut changed = false;
    for line in bytes.split_inclusive(|&b| b == b'\n') {
        let is_vertex = line.first() == Some(&b'v')
            && line
                .get(1)
                .is_some_and(|&b| matches!(b, b' ' | b'\t' | b't' | b'n' | b'p'));
        if !is_vertex {
            out.extend_from_slice(line);
            continue;
        }
        let mut at = 0;
        while at < line.len() {
            let start = at;
            if line[at].is_ascii_whitespace() {
                while at < line.len() && line[at].is_ascii_whitespace() {
                    at += 1;
                }
                out.extend_from_slice(&line[start..at]);
                continue;
            }
            while at < line.len() && !line[at].is_ascii_whitespace() {
                at += 1;
            }
            let token = &line[start..at];
            match parse_hex_float(token) {
                Some(x) => {
                    out.extend_from_slice(format!("{x:?}").as_bytes());
                    changed = true;
                }
                None => out.extend_from_slice(token),
            }
        }
    }
    if changed {
        Cow::Owned(out)
    } else {
        Cow::Borrowed(bytes)
    }
}

/// The value of a C99 hexadecimal float token (`[+-]0x h* [. h*] [p [+-] d+]`,
/// at least one hex digit), correctly rounded to `f64` (to nearest, ties to
/// even; ±inf beyond the largest finite value, which the reader then
/// refuses as non-finite), or `None` if the token is not one.
pub(super) fn parse_hex_float(token: &[u8]) -> Option<f64> {
    let (negative, rest) = match token.first()? {
        b'-' => (true, &token[1..]),
        b'+' => (false, &token[1..]),
        _ => (false, token),
    };
    let rest = rest
        .strip_prefix(b"0x")
        .or_else(|| rest.strip_prefix(b"0X"))?;
    // The significand's bits: the first 64 significant bits kept, the rest
    // only as a sticky bit; `exponent` scales the kept integer.
    let mut significand: u64 = 0;
    let mut sticky = false;
    let mut exponent: i64 = 0;
    let mut digits = 0usize;
    let mut seen_point = false;
    let mut at = 0;
    while at < rest.len() {
        let c = rest[at];
        if c == b'.' && !seen_point {
            seen_point = true;
            at += 1;
            continue;
        }
        let Some(d) = (c as char).to_digit(16) else {
            break;
        };
        digits += 1;
        if significand >> 60 == 0 {
            significand = (significand << 4) | u64::from(d);
            if seen_point {
                exponent -= 4;
            }
        } else {
            sticky |= d != 0;
            if !seen_point {
                exponent += 4;
            }
        }
        at += 1;
    }
    if digits == 0 {
        return None;
    }
    if at < rest.len() {
        if !matches!(rest[at], b'p' | b'P') {
            return None;
        }
        let power = std::str::from_utf8(&rest[at + 1..]).ok()?;
        let power = power.strip_prefix('+').unwrap_or(power);
        let unsigned = power.strip_prefix('-').unwrap_or(power);
        if unsigned.is_empty() || !unsigned.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        // Beyond any f64 either way: saturate (the result is 0 or inf).
        let p: i64 = power.parse().unwrap_or(if power.starts_with('-') {
            -100_000
        } else {
            100_000
        });
        exponent = exponent.saturating_add(p.clamp(-100_000, 100_000));
    }
    let magnitude = round_to_f64(significand, sticky, exponent);
    Some(if negative { -magnitude } else { magnitude })
}

/// `(significand + sticky·ε) · 2^exponent` rounded to nearest `f64`, ties
/// to even, where `sticky` says nonzero bits lie below the significand.
fn round_to_f64(significand: u64, sticky: bool, exponent: i64) -> f64 {
    if significand == 0 {
        return 0.0;
    }
    // Normalise to 64 bits: value = m · 2^(e - 63), m's top bit set.
    let shift = significand.leading_zeros();
    let m = significand << shift;
    let e = exponent - i64::from(shift) + 63;
    // The exponent of the value's leading bit is `e`. f64 keeps 53 bits for
    // e ≥ -1022; below, fewer (subnormals: bits down to 2^-1074).
    let lowest_kept = (e - 52).max(-1074);
    let dropped = lowest_kept - (e - 63);
    if dropped >= 64 + 2 {
        // Below half the smallest subnormal.
        return 0.0;
    }
    // At least 11 bits are dropped (64 held, at most 53 kept).
    let (mut kept, round_bit, below) = if dropped >= 64 {
        // Only the leading bit (dropped = 64) can be the rounding bit.
        let round_bit = dropped == 64;
        let below = dropped > 64 || m << 1 != 0;
        (0, round_bit, below || sticky)
    } else {
        let d = dropped as u32;
        let kept = m >> d;
        let round_bit = (m >> (d - 1)) & 1 == 1;
        let below = (m << (65 - d)) != 0;
        (kept, round_bit, below || sticky)
    };
    if round_bit && (below || kept & 1 == 1) {
        kept += 1;
    }
    // kept · 2^lowest_kept, exact: kept has at most 54 bits.
    let scaled = kept as f64;
    scale_by_power_of_two(scaled, lowest_kept)
}

/// `x · 2^k`, in steps that stay exact (x is an integer of at most 54
/// bits, so the result is exact unless it overflows, where it is inf).
fn scale_by_power_of_two(mut x: f64, mut k: i64) -> f64 {
    while k > 0 {
        let step = k.min(1000);
        x *= 2f64.powi(step as i32);
        k -= step;
    }
    while k < 0 {
        let step = (-k).min(1000);
        // Multiplying by 2^-step is exact while the result is normal; the
        // last step into the subnormal range is exact too, since the
        // rounding above already kept only the bits a subnormal holds.
        x *= 2f64.powi(-(step as i32));
        k += step;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hex(s: &str) -> Option<f64> {
        parse_hex_float(s.as_bytes())
    }

    #[test]
    fn hex_floats_read_exactly() {
        assert_eq!(hex("0x1.8p+1"), Some(3.0));
        assert_eq!(hex("-0x1p-1"), Some(-0.5));
        assert_eq!(hex("0x0p+0"), Some(0.0));
        assert_eq!(hex("0X1.FFFFFFFFFFFFFP+1023"), Some(f64::MAX));
        assert_eq!(hex("0x1p-1074"), Some(f64::from_bits(1)));
        assert_eq!(hex("0x1p-1022"), Some(f64::MIN_POSITIVE));
        assert_eq!(hex("0x1.999999999999ap-4"), Some(0.1));
        assert_eq!(hex("0xa"), Some(10.0));
        assert_eq!(hex("0x.8"), Some(0.5));
        // Every %a of a double reads back to its bits.
        for x in [0.1, 1.0 / 3.0, 1e-310, 6.02e23, -123.456, 1e300, 5e-324] {
            let formatted = format_hex(x);
            assert_eq!(
                hex(&formatted).map(f64::to_bits),
                Some(x.to_bits()),
                "{formatted}"
            );
        }
    }

    #[test]
    fn more_digits_than_f64_holds_round_to_nearest_even() {
        // 1 + 2^-53 is a tie: to even, 1. A bit below it decides upwards.
        assert_eq!(hex("0x1.00000000000008p+0"), Some(1.0));
        assert_eq!(hex("0x1.00000000000008000001p+0"), Some(1.0 + f64::EPSILON));
        assert_eq!(hex("0x1.00000000000018p+0"), Some(1.0 + 2.0 * f64::EPSILON));
        assert_eq!(hex("0x1p+1024"), Some(f64::INFINITY));
        assert_eq!(hex("0x1p-1076"), Some(0.0));
        assert_eq!(hex("0x1.8p-1075"), Some(f64::from_bits(1)));
    }

    #[test]
    fn other_tokens_are_not_hex_floats() {
        for t in [
            "1.5", "0x", "0xg", "0x1p", "0x1p+", "0x1.2.3", "0x1q3", "x1p3", "",
        ] {
            assert_eq!(hex(t), None, "{t}");
        }
    }

    #[test]
    fn only_vertex_lines_are_rewritten_and_lines_stay() {
        let text = b"# 0x1p3\nv 0x1p+1 -0x1.8p+0 0\nvn 0x1p0 0 0\nf 1 2 3\n";
        let out = decimal_floats(text);
        assert_eq!(
            std::str::from_utf8(&out).unwrap(),
            "# 0x1p3\nv 2.0 -1.5 0\nvn 1.0 0 0\nf 1 2 3\n"
        );
        assert!(matches!(decimal_floats(b"v 1 2 3\n"), Cow::Borrowed(_)));
    }

    /// `x` as `%a` writes it (test helper).
    fn format_hex(x: f64) -> String {
        let bits = x.to_bits();
        let sign = if bits >> 63 == 1 { "-" } else { "" };
        let exponent = ((bits >> 52) & 0x7ff) as i64;
        let fraction = bits & ((1 << 52) - 1);
        if exponent == 0 {
            format!("{sign}0x0.{fraction:013x}p-1022")
        } else {
            format!("{sign}0x1.{fraction:013x}p{:+}", exponent - 1023)
        }
    }
}

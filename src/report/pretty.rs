//! A JSON document as indented text: exactly what `serde_json::to_string_pretty` writes (two-space
//! indentation, `"key": value`, `[]` and `{}` when empty), into one string sized up front. The
//! documents of large robots are megabytes of expressions that need no escaping; they are copied
//! whole, where the general serializer reads them byte by byte into a string that grows.

use serde_json::Value;

/// `value` as serde_json's pretty text.
pub fn to_pretty(value: &Value) -> String {
    let mut out = String::with_capacity(size(value, 0));
    write(&mut out, value, 0);
    out
}

/// An upper estimate of the text's length at `depth` (strings, their quotes and separators, and
/// each line's indentation), so the output is allocated once.
fn size(value: &Value, depth: usize) -> usize {
    let line = 2 * (depth + 1) + 4;
    match value {
        Value::String(s) => s.len() + 2,
        Value::Array(items) => {
            items
                .iter()
                .map(|v| line + size(v, depth + 1))
                .sum::<usize>()
                + line
        }
        Value::Object(map) => {
            map.iter()
                .map(|(k, v)| line + k.len() + 4 + size(v, depth + 1))
                .sum::<usize>()
                + line
        }
        _ => 24,
    }
}

/// Whether a string is written as it stands between quotes: no quote, backslash or control
/// character (which JSON escapes).
fn plain(s: &str) -> bool {
    // Read whole (no early exit), so the loop runs over wide registers.
    !s.bytes().fold(false, |any, b| {
        any | (b < 0x20) | (b == b'"') | (b == b'\\')
    })
}

/// A string as a JSON string literal.
fn write_str(out: &mut String, s: &str) {
    if plain(s) {
        out.push('"');
        out.push_str(s);
        out.push('"');
    } else {
        out.push_str(&serde_json::to_string(s).expect("a string serialises"));
    }
}

/// A new line indented to `depth`.
fn newline(out: &mut String, depth: usize) {
    out.push('\n');
    for _ in 0..depth {
        out.push_str("  ");
    }
}

fn write(out: &mut String, value: &Value, depth: usize) {
    match value {
        Value::String(s) => write_str(out, s),
        Value::Array(items) if items.is_empty() => out.push_str("[]"),
        Value::Array(items) => {
            out.push('[');
            for (i, v) in items.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                newline(out, depth + 1);
                write(out, v, depth + 1);
            }
            newline(out, depth);
            out.push(']');
        }
        Value::Object(map) if map.is_empty() => out.push_str("{}"),
        Value::Object(map) => {
            out.push('{');
            for (i, (k, v)) in map.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                newline(out, depth + 1);
                write_str(out, k);
                out.push_str(": ");
                write(out, v, depth + 1);
            }
            newline(out, depth);
            out.push('}');
        }
        // null, booleans and numbers as serde_json writes them.
        other => out.push_str(&serde_json::to_string(other).expect("a scalar serialises")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn writes_what_serde_json_writes() {
        let docs = [
            json!(null),
            json!([]),
            json!({}),
            json!("a \"quoted\" \\ line\nbreak\ttab \u{1} and ü"),
            json!({
                "robot": "ppp", "frame": null, "ok": true, "n": -3, "x": 0.1, "big": 1e300,
                "empty": [], "none": {}, "nested": [[1, 2], [], [{"i": 1, "value": "m1*g"}]],
                "tau": ["(m1+m2)*qdd1", "-g*m2*cos(q1)"],
            }),
        ];
        for d in docs {
            assert_eq!(
                to_pretty(&d),
                serde_json::to_string_pretty(&d).expect("JSON")
            );
        }
    }
}

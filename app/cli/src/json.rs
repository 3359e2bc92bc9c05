//! A tiny ordered JSON writer (field order as documented; no dependency on
//! map ordering). Non-finite numbers are written as `null` — JSON has no
//! Infinity/NaN — and callers say so in a separate field.

/// A JSON number, or `null` when `x` is NaN or ±∞.
pub fn num(x: f64) -> String {
    if x.is_finite() {
        // serde_json prints the shortest representation that round-trips.
        serde_json::to_string(&x).unwrap_or_else(|_| "null".into())
    } else {
        "null".into()
    }
}

/// A JSON string literal.
pub fn string(s: &str) -> String {
    serde_json::to_string(s).unwrap_or_else(|_| "\"\"".into())
}

/// A JSON array of numbers.
pub fn array(xs: &[f64]) -> String {
    let items: Vec<String> = xs.iter().map(|&x| num(x)).collect();
    format!("[{}]", items.join(", "))
}

/// A JSON array of number arrays, one row per line, indented for a field.
pub fn matrix(rows: &[Vec<f64>]) -> String {
    if rows.is_empty() {
        return "[]".into();
    }
    let items: Vec<String> = rows.iter().map(|r| format!("    {}", array(r))).collect();
    format!("[\n{}\n  ]", items.join(",\n"))
}

/// An object written field by field, in insertion order.
#[derive(Default)]
pub struct Object {
    fields: Vec<(String, String)>,
}

impl Object {
    /// Add `key` with an already-encoded JSON value.
    pub fn raw(&mut self, key: &str, value: String) -> &mut Self {
        self.fields.push((key.to_string(), value));
        self
    }

    /// The object, one field per line.
    pub fn render(&self) -> String {
        let body: Vec<String> = self
            .fields
            .iter()
            .map(|(k, v)| format!("  {}: {v}", string(k)))
            .collect();
        format!("{{\n{}\n}}", body.join(",\n"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_valid_ordered_json() {
        let mut o = Object::default();
        o.raw("psi", num(1.5))
            .raw("bad", num(f64::INFINITY))
            .raw("v", array(&[1.0, f64::NAN, -2e-300]))
            .raw("m", matrix(&[vec![1.0, 2.0], vec![3.0, 4.0]]))
            .raw("name", string("a \"q\""));
        let text = o.render();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["psi"], 1.5);
        assert!(v["bad"].is_null());
        assert!(v["v"][1].is_null());
        assert_eq!(v["v"][2], -2e-300);
        assert_eq!(v["m"][1][0], 3.0);
        assert_eq!(v["name"], "a \"q\"");
        assert!(text.find("\"psi\"").unwrap() < text.find("\"name\"").unwrap());
    }
}

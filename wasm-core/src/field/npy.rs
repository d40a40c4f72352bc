//! NumPy `.npy` (format version 1.0) for little-endian float32 arrays in C order.
//!
//! Reading trusts nothing it has not checked: the header is parsed as the Python literal it is
//! (a dict with exactly the keys `'descr'`, `'fortran_order'` and `'shape'`, each of its type),
//! its declared length is held to [`MAX_HEADER_LEN`] before it is read, and only the bytes the
//! shape needs are read. Given the file's size ([`read_f32_sized`]), the header's and the
//! data's lengths are checked against it before anything large is read or allocated.

use std::io::{self, Read, Write};

const MAGIC: &[u8] = b"\x93NUMPY";

/// Longest header read: NumPy's own reader refuses longer ones by default (its
/// `max_header_size`), and a float32 array's header is under 200 bytes.
pub const MAX_HEADER_LEN: usize = 10_000;

/// Writes `data` with `shape` as a `<f4` C-order array.
pub fn write_f32(mut w: impl Write, shape: &[usize], data: &[f32]) -> io::Result<()> {
    assert_eq!(
        shape.iter().product::<usize>(),
        data.len(),
        "shape does not match data"
    );
    let dims: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    let tuple = if dims.len() == 1 {
        format!("({},)", dims[0])
    } else {
        format!("({})", dims.join(", "))
    };
    let mut header = format!("{{'descr': '<f4', 'fortran_order': False, 'shape': {tuple}, }}");
    // Pad with spaces so that magic + version + length + header + '\n' is a multiple of 64.
    let unpadded = MAGIC.len() + 2 + 2 + header.len() + 1;
    header.push_str(&" ".repeat((64 - unpadded % 64) % 64));
    header.push('\n');
    w.write_all(MAGIC)?;
    w.write_all(&[1, 0])?;
    w.write_all(&(header.len() as u16).to_le_bytes())?;
    w.write_all(header.as_bytes())?;
    let mut bytes = Vec::with_capacity(data.len() * 4);
    for v in data {
        bytes.extend_from_slice(&v.to_le_bytes());
    }
    w.write_all(&bytes)
}

fn invalid(msg: impl Into<String>) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, msg.into())
}

/// What the header says: the array's shape, and where its data starts.
struct Header {
    shape: Vec<usize>,
    /// Bytes of data the shape needs (4 a value).
    data_len: u64,
    /// Bytes before the data: magic, version, length and header.
    data_offset: u64,
}

/// Reads a `<f4` C-order array (format 1.0–3.0) from a stream of unknown length; returns its
/// shape and values. Reads the header and exactly the bytes its shape needs (growing the
/// buffer as they arrive, so a short stream never costs the declared size), then refuses the
/// array if one more byte follows.
pub fn read_f32(mut r: impl Read) -> io::Result<(Vec<usize>, Vec<f32>)> {
    let header = read_header(&mut r, None)?;
    let mut bytes = Vec::new();
    r.by_ref().take(header.data_len).read_to_end(&mut bytes)?;
    if (bytes.len() as u64) < header.data_len {
        return Err(invalid(format!(
            "the data ends after {} of the {} bytes shape {:?} needs",
            bytes.len(),
            header.data_len,
            header.shape
        )));
    }
    let mut next = [0u8; 1];
    if r.read(&mut next)? > 0 {
        return Err(invalid(format!(
            "more data follows the {} bytes shape {:?} needs",
            header.data_len, header.shape
        )));
    }
    let data = bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    Ok((header.shape, data))
}

/// Reads a `<f4` C-order array from a file of `file_len` bytes: the header's declared length,
/// then the data's, are checked against the file's size before they are read, so a file that
/// claims more than it holds, or holds more than its shape needs, is refused at once.
pub fn read_f32_sized(mut r: impl Read, file_len: u64) -> io::Result<(Vec<usize>, Vec<f32>)> {
    let header = read_header(&mut r, Some(file_len))?;
    let expected = header.data_offset + header.data_len;
    if expected != file_len {
        let shape = &header.shape;
        return Err(invalid(if file_len < expected {
            format!(
                "shape {shape:?} needs {} bytes of data, the file holds {}",
                header.data_len,
                file_len - header.data_offset
            )
        } else {
            format!(
                "the file holds {} bytes after the {} its shape {shape:?} needs",
                file_len - expected,
                header.data_len
            )
        }));
    }
    let mut data = vec![0f32; (header.data_len / 4) as usize];
    r.read_exact(bytemuck::cast_slice_mut(&mut data))?;
    for v in &mut data {
        *v = f32::from_bits(u32::from_le(v.to_bits()));
    }
    Ok((header.shape, data))
}

/// Reads and checks the magic, the version, the header's length (against [`MAX_HEADER_LEN`]
/// and the file's size, when known) and the header itself.
fn read_header(r: &mut impl Read, file_len: Option<u64>) -> io::Result<Header> {
    let mut magic = [0u8; 8];
    r.read_exact(&mut magic)
        .map_err(|_| invalid("not a .npy file (shorter than its magic string)"))?;
    if &magic[..6] != MAGIC {
        return Err(invalid("not a .npy file (bad magic)"));
    }
    let (major, minor) = (magic[6], magic[7]);
    let length_bytes = match (major, minor) {
        (1, 0) => 2,
        (2 | 3, 0) => 4,
        _ => {
            return Err(invalid(format!(
                "unsupported .npy version {major}.{minor} (1.0, 2.0 and 3.0 are read)"
            )))
        }
    };
    let mut b = [0u8; 4];
    r.read_exact(&mut b[..length_bytes])
        .map_err(|_| invalid("the file ends inside the header's length"))?;
    let header_len = u32::from_le_bytes(b) as usize;
    let data_offset = (8 + length_bytes + header_len) as u64;
    if header_len > MAX_HEADER_LEN {
        return Err(invalid(format!(
            "the header claims {header_len} bytes; at most {MAX_HEADER_LEN} are read"
        )));
    }
    if let Some(len) = file_len.filter(|&len| len < data_offset) {
        return Err(invalid(format!(
            "the header claims {header_len} bytes, the file holds {} after its length",
            len - (8 + length_bytes) as u64
        )));
    }
    let mut text = vec![0u8; header_len];
    r.read_exact(&mut text)
        .map_err(|_| invalid(format!("the file ends inside its {header_len}-byte header")))?;
    // Versions 1 and 2 are latin-1, 3 is UTF-8; a float32 header is ASCII either way.
    let text = std::str::from_utf8(&text)
        .ok()
        .filter(|t| t.is_ascii())
        .ok_or_else(|| invalid("the header is not ASCII text"))?;
    let shape = parse_header(text).map_err(|e| invalid(format!("header {text:?}: {e}")))?;
    let data_len = shape
        .iter()
        .try_fold(4u64, |acc, &d| acc.checked_mul(d as u64))
        .ok_or_else(|| invalid(format!("shape {shape:?} is too large")))?;
    Ok(Header {
        shape,
        data_len,
        data_offset,
    })
}

/// A value of the header's dict.
#[derive(Debug, PartialEq)]
enum Literal {
    Str(String),
    Bool(bool),
    Tuple(Vec<usize>),
}

/// Parses the header, `{'descr': '<f4', 'fortran_order': False, 'shape': (…), }` padded with
/// spaces and ended by a newline, as a Python dict literal; returns the shape.
fn parse_header(text: &str) -> Result<Vec<usize>, String> {
    let mut p = Parser {
        s: text.as_bytes(),
        i: 0,
    };
    let dict = p.dict()?;
    p.space();
    if p.i != p.s.len() {
        return Err("text follows the dict".into());
    }
    let get = |key: &str| {
        dict.iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v)
            .ok_or_else(|| format!("no '{key}'"))
    };
    for (i, (key, _)) in dict.iter().enumerate() {
        if !["descr", "fortran_order", "shape"].contains(&key.as_str()) {
            return Err(format!(
                "unknown key '{key}' (the keys are 'descr', 'fortran_order' and 'shape')"
            ));
        }
        if dict[..i].iter().any(|(k, _)| k == key) {
            return Err(format!("'{key}' twice"));
        }
    }
    match get("descr")? {
        Literal::Str(d) if d == "<f4" => {}
        Literal::Str(d) => {
            return Err(format!(
                "dtype '{d}': only little-endian float32 ('<f4') arrays are read"
            ))
        }
        _ => return Err("'descr' must be a string".into()),
    }
    match get("fortran_order")? {
        Literal::Bool(false) => {}
        Literal::Bool(true) => {
            return Err(
                "a Fortran-ordered array (fortran_order: True); only C order is read".into(),
            )
        }
        _ => return Err("'fortran_order' must be True or False".into()),
    }
    match get("shape")? {
        Literal::Tuple(shape) => Ok(shape.clone()),
        _ => Err("'shape' must be a tuple of whole numbers".into()),
    }
}

/// A cursor over the header's bytes.
struct Parser<'a> {
    s: &'a [u8],
    i: usize,
}

impl Parser<'_> {
    fn space(&mut self) {
        while self.s.get(self.i).is_some_and(|c| c.is_ascii_whitespace()) {
            self.i += 1;
        }
    }

    /// Skips whitespace; takes `c` if it comes next.
    fn eat(&mut self, c: u8) -> bool {
        self.space();
        let found = self.s.get(self.i) == Some(&c);
        if found {
            self.i += 1;
        }
        found
    }

    fn expect(&mut self, c: u8) -> Result<(), String> {
        if self.eat(c) {
            Ok(())
        } else {
            Err(format!("expected '{}' at byte {}", c as char, self.i))
        }
    }

    /// `{key: value, …}`, a trailing comma allowed.
    fn dict(&mut self) -> Result<Vec<(String, Literal)>, String> {
        self.expect(b'{')?;
        let mut out = Vec::new();
        while !self.eat(b'}') {
            let key = self.string()?;
            self.expect(b':')?;
            out.push((key, self.value()?));
            if !self.eat(b',') {
                self.expect(b'}')?;
                break;
            }
        }
        Ok(out)
    }

    /// A string in single or double quotes, without escapes.
    fn string(&mut self) -> Result<String, String> {
        self.space();
        let quote = match self.s.get(self.i) {
            Some(&q @ (b'\'' | b'"')) => q,
            _ => return Err(format!("expected a string at byte {}", self.i)),
        };
        let start = self.i + 1;
        let len = self.s[start..]
            .iter()
            .position(|&c| c == quote || c == b'\\')
            .filter(|&n| self.s[start + n] == quote)
            .ok_or_else(|| format!("a string at byte {} is not closed (or escapes)", self.i))?;
        self.i = start + len + 1;
        Ok(String::from_utf8_lossy(&self.s[start..start + len]).into_owned())
    }

    fn value(&mut self) -> Result<Literal, String> {
        self.space();
        let rest = &self.s[self.i..];
        if rest.starts_with(b"True") || rest.starts_with(b"False") {
            let yes = rest[0] == b'T';
            self.i += if yes { 4 } else { 5 };
            return Ok(Literal::Bool(yes));
        }
        match rest.first() {
            Some(b'\'' | b'"') => self.string().map(Literal::Str),
            Some(b'(') => self.tuple().map(Literal::Tuple),
            _ => Err(format!(
                "expected a string, True, False or a tuple at byte {}",
                self.i
            )),
        }
    }

    /// `()`, `(n,)` or `(n, m, …)` (a trailing comma allowed) of whole numbers.
    fn tuple(&mut self) -> Result<Vec<usize>, String> {
        self.expect(b'(')?;
        let mut out = Vec::new();
        while !self.eat(b')') {
            out.push(self.integer()?);
            if !self.eat(b',') {
                if out.len() == 1 {
                    // `(n)` is a number in parentheses, not a tuple.
                    return Err("a one-dimensional shape is written (n,)".into());
                }
                self.expect(b')')?;
                break;
            }
        }
        Ok(out)
    }

    fn integer(&mut self) -> Result<usize, String> {
        self.space();
        let start = self.i;
        while self.s.get(self.i).is_some_and(u8::is_ascii_digit) {
            self.i += 1;
        }
        std::str::from_utf8(&self.s[start..self.i])
            .ok()
            .filter(|d| !d.is_empty())
            .and_then(|d| d.parse().ok())
            .ok_or_else(|| format!("expected a whole number at byte {start}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn array(header: &str, values: usize) -> Vec<u8> {
        let mut buf = MAGIC.to_vec();
        buf.extend_from_slice(&[1, 0]);
        buf.extend_from_slice(&(header.len() as u16).to_le_bytes());
        buf.extend_from_slice(header.as_bytes());
        buf.extend(std::iter::repeat_n(0u8, values * 4));
        buf
    }

    #[test]
    fn round_trip_and_alignment() {
        let data: Vec<f32> = (0..24).map(|i| i as f32 * 0.5 - 3.0).collect();
        let mut buf = Vec::new();
        write_f32(&mut buf, &[2, 3, 4], &data).unwrap();
        let header_len = u16::from_le_bytes([buf[8], buf[9]]) as usize;
        assert_eq!((10 + header_len) % 64, 0);
        assert_eq!(buf[10 + header_len - 1], b'\n');
        let (shape, back) = read_f32(&buf[..]).unwrap();
        assert_eq!(shape, vec![2, 3, 4]);
        assert_eq!(back, data);
        let (shape, back) = read_f32_sized(&buf[..], buf.len() as u64).unwrap();
        assert_eq!((shape, back), (vec![2, 3, 4], data));
        let mut one = Vec::new();
        write_f32(&mut one, &[1], &[7.0]).unwrap();
        assert_eq!(read_f32(&one[..]).unwrap(), (vec![1], vec![7.0]));
    }

    #[test]
    fn rejects_other_dtypes_and_truncation() {
        let mut buf = Vec::new();
        write_f32(&mut buf, &[4], &[1.0, 2.0, 3.0, 4.0]).unwrap();
        assert!(read_f32(&buf[..buf.len() - 1]).is_err());
        assert!(read_f32_sized(&buf[..buf.len() - 1], buf.len() as u64 - 1).is_err());
        let text = String::from_utf8_lossy(&buf).replace("<f4", "<f8");
        assert!(read_f32(text.as_bytes()).is_err());
        assert!(read_f32(&b"hello world"[..]).is_err());
    }

    #[test]
    fn the_header_is_the_python_literal_not_a_substring() {
        let ok = "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }    \n";
        assert_eq!(read_f32(&array(ok, 6)[..]).unwrap().0, vec![2, 3]);
        // Other spellings Python reads the same: double quotes, no trailing comma, key order.
        let ok = "{\"shape\": (6,), \"fortran_order\": False, \"descr\": \"<f4\"}\n";
        assert_eq!(read_f32(&array(ok, 6)[..]).unwrap().0, vec![6]);
        assert_eq!(
            read_f32(&array("{'descr':'<f4','fortran_order':False,'shape':()}", 1)[..])
                .unwrap()
                .0,
            Vec::<usize>::new()
        );
        for (header, why) in [
            // A Fortran-ordered array whose extra key holds the text a substring match sought.
            (
                "{'descr': '<f4', 'fortran_order': True, 'shape': (2, 3), 'x': \"'fortran_order': False\"}",
                "unknown key 'x'",
            ),
            (
                "{'descr': '<f4', 'fortran_order': True, 'shape': (2, 3), }",
                "Fortran-ordered",
            ),
            (
                "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), 'shape': (6,)}",
                "'shape' twice",
            ),
            (
                "{'descr': '<f4', 'fortran_order': 0, 'shape': (2, 3)}",
                "expected a string, True, False or a tuple",
            ),
            (
                "{'descr': '<f4', 'fortran_order': 'False', 'shape': (2, 3)}",
                "'fortran_order' must be True or False",
            ),
            (
                "{'descr': '<f4', 'fortran_order': False, 'shape': (6)}",
                "(n,)",
            ),
            (
                "{'descr': '<f4', 'fortran_order': False, 'shape': (2, -3)}",
                "whole number",
            ),
            ("{'descr': '<f4', 'fortran_order': False}", "no 'shape'"),
            (
                "{'descr': '<f4', 'fortran_order': False, 'shape': (6,)} # 'x'",
                "text follows the dict",
            ),
            (
                "{'descr': '>f4', 'fortran_order': False, 'shape': (6,)}",
                "only little-endian float32",
            ),
            (
                "{'descr': '<f4', 'fortran_order': False, 'shape': (6,), 'descr\\x': 1}",
                "escapes",
            ),
        ] {
            let e = read_f32(&array(header, 6)[..]).unwrap_err().to_string();
            assert!(e.contains(why), "{header}: {e}");
        }
    }

    /// A stream of a valid header, then zeros without end, counting the bytes read from it.
    struct Endless {
        head: Vec<u8>,
        read: u64,
    }

    impl Read for Endless {
        fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
            let at = self.read as usize;
            let n = if at < self.head.len() {
                let n = buf.len().min(self.head.len() - at);
                buf[..n].copy_from_slice(&self.head[at..at + n]);
                n
            } else {
                buf.fill(0);
                buf.len()
            };
            self.read += n as u64;
            Ok(n)
        }
    }

    #[test]
    fn only_the_bytes_the_shape_needs_are_read() {
        let head = array(
            "{'descr': '<f4', 'fortran_order': False, 'shape': (4,), }",
            0,
        );
        let mut stream = Endless {
            head: head.clone(),
            read: 0,
        };
        let e = read_f32(&mut stream).unwrap_err().to_string();
        assert!(e.contains("more data follows the 16 bytes"), "{e}");
        assert!(
            stream.read <= head.len() as u64 + 16 + 8192,
            "{}",
            stream.read
        );
        // Given the size (a 6 GiB tail), refused before the data is read.
        let len = head.len() as u64 + 16 + (6 << 30);
        let mut stream = Endless { head, read: 0 };
        let e = read_f32_sized(&mut stream, len).unwrap_err().to_string();
        assert!(e.contains("6442450944 bytes after the 16"), "{e}");
        assert!(stream.read < 200, "{}", stream.read);
    }

    #[test]
    fn declared_lengths_beyond_the_file_are_refused_before_allocating() {
        // 13 bytes that claim a 4 GiB header (version 2.0, a 32-bit length).
        let mut tiny = MAGIC.to_vec();
        tiny.extend_from_slice(&[2, 0, 0xff, 0xff, 0xff, 0xff, b'{']);
        assert_eq!(tiny.len(), 13);
        for e in [
            read_f32(&tiny[..]).unwrap_err(),
            read_f32_sized(&tiny[..], 13).unwrap_err(),
        ] {
            assert!(e.to_string().contains("at most 10000"), "{e}");
        }
        // A header within the limit but past the file's end.
        let mut short = MAGIC.to_vec();
        short.extend_from_slice(&[1, 0, 0x10, 0x27, b'{']);
        let e = read_f32_sized(&short[..], short.len() as u64).unwrap_err();
        assert!(e.to_string().contains("the file holds 1 after"), "{e}");
        // A shape of 2^40 values in a small file: refused by the size, nothing allocated.
        let huge = array(
            "{'descr': '<f4', 'fortran_order': False, 'shape': (1048576, 1048576), }",
            2,
        );
        let e = read_f32_sized(&huge[..], huge.len() as u64).unwrap_err();
        assert!(e.to_string().contains("needs 4398046511104 bytes"), "{e}");
        assert!(read_f32(&huge[..]).is_err());
        let overflow = array(
            "{'descr': '<f4', 'fortran_order': False, 'shape': (18446744073709551615, 2), }",
            0,
        );
        assert!(read_f32(&overflow[..])
            .unwrap_err()
            .to_string()
            .contains("too large"));
        assert!(read_f32(&MAGIC[..4]).is_err());
    }
}

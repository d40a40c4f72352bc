//! NumPy `.npy` (format version 1.0) for little-endian float32 arrays in C order.

use std::io::{self, Read, Write};

const MAGIC: &[u8] = b"\x93NUMPY";

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

/// Reads a `<f4` C-order array (format 1.0–3.0); returns its shape and values.
pub fn read_f32(mut r: impl Read) -> io::Result<(Vec<usize>, Vec<f32>)> {
    let mut magic = [0u8; 8];
    r.read_exact(&mut magic)?;
    if &magic[..6] != MAGIC {
        return Err(invalid("not a .npy file (bad magic)"));
    }
    let header_len = match magic[6] {
        1 => {
            let mut b = [0u8; 2];
            r.read_exact(&mut b)?;
            u16::from_le_bytes(b) as usize
        }
        2 | 3 => {
            let mut b = [0u8; 4];
            r.read_exact(&mut b)?;
            u32::from_le_bytes(b) as usize
        }
        v => return Err(invalid(format!("unsupported .npy version {v}"))),
    };
    let mut header = vec![0u8; header_len];
    r.read_exact(&mut header)?;
    let header = String::from_utf8(header).map_err(|_| invalid("header is not text"))?;
    let compact: String = header.chars().filter(|c| !c.is_whitespace()).collect();
    if !compact.contains("'descr':'<f4'") {
        return Err(invalid(
            "only little-endian float32 ('<f4') arrays are supported",
        ));
    }
    if !compact.contains("'fortran_order':False") {
        return Err(invalid("only C-order arrays are supported"));
    }
    let start = compact
        .find("'shape':(")
        .ok_or_else(|| invalid("header has no shape"))?
        + "'shape':(".len();
    let end = compact[start..]
        .find(')')
        .ok_or_else(|| invalid("header shape is not closed"))?;
    let shape = compact[start..start + end]
        .split(',')
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.parse::<usize>()
                .map_err(|_| invalid(format!("bad dimension {s:?}")))
        })
        .collect::<io::Result<Vec<usize>>>()?;
    let count = shape
        .iter()
        .try_fold(1usize, |acc, &d| acc.checked_mul(d))
        .ok_or_else(|| invalid("shape too large"))?;
    let mut bytes = Vec::new();
    r.read_to_end(&mut bytes)?;
    if bytes.len() != count * 4 {
        return Err(invalid(format!(
            "expected {} bytes of data for shape {shape:?}, found {}",
            count * 4,
            bytes.len()
        )));
    }
    let data = bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    Ok((shape, data))
}

#[cfg(test)]
mod tests {
    use super::*;

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
    }

    #[test]
    fn rejects_other_dtypes_and_truncation() {
        let mut buf = Vec::new();
        write_f32(&mut buf, &[4], &[1.0, 2.0, 3.0, 4.0]).unwrap();
        assert!(read_f32(&buf[..buf.len() - 1]).is_err());
        let text = String::from_utf8_lossy(&buf).replace("<f4", "<f8");
        assert!(read_f32(text.as_bytes()).is_err());
        assert!(read_f32(&b"hello world"[..]).is_err());
    }
}

//! OpenVDB files (`.vdb`, file format version 224, as OpenVDB 10 and later read and write
//! them), written without OpenVDB: no Rust crate writes the format (`vdb-rs` only reads it),
//! so this module follows OpenVDB's own writer (`io/Archive.cc`, `io/GridDescriptor.cc`,
//! `tree/RootNode.h`, `tree/InternalNode.h`, `tree/LeafNode.h`, `io/Compression.h`) field by
//! field. Everything is little-endian.
//!
//! ```text
//! file      magic 0x56444220 (int64) · format version 224 (u32) · library 10.0 (2 × u32)
//!           · has grid offsets 1 (u8) · UUID (36 ASCII characters) · file metadata
//!           · grid count (i32) · the grids
//! grid      name, type ("Tree_float_5_4_3", "Tree_vec3s_5_4_3"), instance parent ("")
//!           (strings: u32 length then bytes) · grid, block and end positions (3 × i64,
//!           absolute) · compression flags (u32: 2, "active values") · metadata · transform
//!           · topology · buffers
//! metadata  count (u32), then per item, in name order: name, type name, value size (u32),
//!           value
//! transform map type name, then its vectors (each 3 × f64): UniformScaleMap and ScaleMap
//!           scale, voxel size, 1/scale, 1/scale², 1/(2 scale); the ...TranslateMap forms
//!           put the translation first
//! topology  buffer count 1 (i32) · root: background, tile count 0, child count (u32 each),
//!           then per 32³ internal node, in coordinate order: its origin (3 × i32) and
//!           its topology: child mask, value mask (512 u64 each), compressed values, then
//!           per 16³ child in offset order: child mask, value mask (64 u64 each), compressed
//!           values, then per 8³ leaf in offset order its value mask (8 u64)
//! buffers   per leaf, in the same order: value mask (8 u64) · compressed values
//! values    (compression "active values", OpenVDB's mask compression): one byte 0
//!           (NO_MASK_OR_INACTIVE_VALS: every inactive value is the background), then the
//!           active values only, in offset order
//! ```
//!
//! A leaf holds 8³ voxels, index n = 64·(x mod 8) + 8·(y mod 8) + (z mod 8) (z fastest); an
//! internal node 16³ leaves or 32³ of those, indexed the same way; the root maps the origins
//! of the 4096³ internal nodes. Inactive voxels hold the background (zero). Voxel (i, j, k)
//! of a grid lies at `transform(i, j, k)` in world space (its centre).

use std::collections::BTreeMap;

/// The file format version written (OPENVDB_FILE_VERSION_MULTIPASS_IO, read by OpenVDB 6 on).
pub const FILE_VERSION: u32 = 224;
/// The library version written in the header: the OpenVDB release this writer follows.
pub const LIBRARY_VERSION: (u32, u32) = (10, 0);
const MAGIC: i64 = 0x5644_4220;
/// Compression flags: COMPRESS_ACTIVE_MASK, and neither zip nor Blosc.
const COMPRESS_ACTIVE_MASK: u32 = 0x2;
/// Mask-compression metadata: every inactive value is the background.
const NO_MASK_OR_INACTIVE_VALS: u8 = 0;

/// Voxels per leaf edge (log2 3), leaves per lower internal edge (log2 4), lower nodes per
/// upper internal edge (log2 5): OpenVDB's default tree, `Tree_*_5_4_3`.
pub const LEAF_DIM: i32 = 8;
const LOWER_DIM: i32 = 16;
const UPPER_DIM: i32 = 32;
/// Voxels along an edge of a lower (128) and an upper (4096) internal node.
const LOWER_SPAN: i32 = LEAF_DIM * LOWER_DIM;
const UPPER_SPAN: i32 = LOWER_SPAN * UPPER_DIM;

/// A voxel value type OpenVDB knows.
pub trait VoxelValue: Copy + PartialEq {
    /// OpenVDB's name of the type (`typeNameAsString`).
    const TYPE_NAME: &'static str;
    /// The background (inactive) value: zero.
    const ZERO: Self;
    fn write(&self, out: &mut Vec<u8>);
}

impl VoxelValue for f32 {
    const TYPE_NAME: &'static str = "float";
    const ZERO: Self = 0.0;
    fn write(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

impl VoxelValue for [f32; 3] {
    const TYPE_NAME: &'static str = "vec3s";
    const ZERO: Self = [0.0; 3];
    fn write(&self, out: &mut Vec<u8>) {
        for v in self {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
}

/// One 8³ leaf: its voxels (index [`leaf_offset`]) and which of them are active.
#[derive(Debug, Clone, PartialEq)]
pub struct Leaf<T> {
    pub values: Vec<T>,
    pub mask: [u64; 8],
}

impl<T: VoxelValue> Leaf<T> {
    pub fn new() -> Self {
        Self {
            values: vec![T::ZERO; 512],
            mask: [0; 8],
        }
    }

    pub fn is_active(&self, n: usize) -> bool {
        self.mask[n >> 6] >> (n & 63) & 1 == 1
    }

    pub fn set_active(&mut self, n: usize, on: bool) {
        if on {
            self.mask[n >> 6] |= 1 << (n & 63);
        } else {
            self.mask[n >> 6] &= !(1 << (n & 63));
        }
    }

    pub fn active_count(&self) -> u64 {
        self.mask.iter().map(|w| u64::from(w.count_ones())).sum()
    }
}

impl<T: VoxelValue> Default for Leaf<T> {
    fn default() -> Self {
        Self::new()
    }
}

/// The index of voxel (i, j, k) inside its leaf (OpenVDB's `LeafNode::coordToOffset`).
pub fn leaf_offset(i: i32, j: i32, k: i32) -> usize {
    (((i & 7) << 6) | ((j & 7) << 3) | (k & 7)) as usize
}

/// The origin of the leaf holding voxel (i, j, k).
pub fn leaf_origin(i: i32, j: i32, k: i32) -> [i32; 3] {
    [i & !7, j & !7, k & !7]
}

/// A sparse grid: its leaves by origin (coordinate order, as OpenVDB's root orders them).
pub type Leaves<T> = BTreeMap<[i32; 3], Leaf<T>>;

/// Index space to world space: OpenVDB's linear maps without rotation. World = scale ⊙ index
/// (+ translation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transform {
    pub scale: [f64; 3],
    pub translation: [f64; 3],
}

impl Transform {
    /// Voxels of side `h` (m), voxel (0, 0, 0) centred at the origin.
    pub fn uniform(h: f64) -> Self {
        Self {
            scale: [h; 3],
            translation: [0.0; 3],
        }
    }

    /// The world position of index point (i, j, k).
    pub fn world(&self, ijk: [f64; 3]) -> [f64; 3] {
        [0, 1, 2].map(|a| self.scale[a] * ijk[a] + self.translation[a])
    }

    fn write(&self, out: &mut Vec<u8>) {
        let uniform = self.scale[0] == self.scale[1] && self.scale[1] == self.scale[2];
        let translated = self.translation != [0.0; 3];
        let name = match (uniform, translated) {
            (true, false) => "UniformScaleMap",
            (false, false) => "ScaleMap",
            (true, true) => "UniformScaleTranslateMap",
            (false, true) => "ScaleTranslateMap",
        };
        write_string(out, name);
        let vec3 = |out: &mut Vec<u8>, v: [f64; 3]| {
            for x in v {
                out.extend_from_slice(&x.to_le_bytes());
            }
        };
        if translated {
            vec3(out, self.translation);
        }
        let inverse = self.scale.map(|s| 1.0 / s);
        vec3(out, self.scale);
        vec3(out, self.scale.map(f64::abs));
        vec3(out, inverse);
        vec3(out, inverse.map(|v| v * v));
        vec3(out, inverse.map(|v| v / 2.0));
    }
}

/// A grid's class (OpenVDB's `GridClass`, stored as the metadata `class`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GridClass {
    Unknown,
    FogVolume,
}

impl GridClass {
    fn name(self) -> &'static str {
        match self {
            Self::Unknown => "unknown",
            Self::FogVolume => "fog volume",
        }
    }
}

/// A metadata value (OpenVDB's typed metadata).
#[derive(Debug, Clone, PartialEq)]
pub enum Meta {
    String(String),
    Bool(bool),
    Float(f32),
    Double(f64),
    Int64(i64),
    Vec3i([i32; 3]),
    Vec3d([f64; 3]),
}

impl Meta {
    fn type_name(&self) -> &'static str {
        match self {
            Self::String(_) => "string",
            Self::Bool(_) => "bool",
            Self::Float(_) => "float",
            Self::Double(_) => "double",
            Self::Int64(_) => "int64",
            Self::Vec3i(_) => "vec3i",
            Self::Vec3d(_) => "vec3d",
        }
    }

    fn value(&self) -> Vec<u8> {
        match self {
            Self::String(s) => s.as_bytes().to_vec(),
            Self::Bool(b) => vec![u8::from(*b)],
            Self::Float(v) => v.to_le_bytes().to_vec(),
            Self::Double(v) => v.to_le_bytes().to_vec(),
            Self::Int64(v) => v.to_le_bytes().to_vec(),
            Self::Vec3i(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            Self::Vec3d(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
        }
    }
}

/// A metadata map, written in name order (OpenVDB's `MetaMap` is a `std::map`).
pub type MetaMap = BTreeMap<String, Meta>;

fn write_string(out: &mut Vec<u8>, s: &str) {
    out.extend_from_slice(&(s.len() as u32).to_le_bytes());
    out.extend_from_slice(s.as_bytes());
}

fn write_meta(out: &mut Vec<u8>, meta: &MetaMap) {
    out.extend_from_slice(&(meta.len() as u32).to_le_bytes());
    for (name, value) in meta {
        write_string(out, name);
        write_string(out, value.type_name());
        let bytes = value.value();
        out.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
        out.extend_from_slice(&bytes);
    }
}

/// One grid to write: a name, a class, its transform, its leaves and its own metadata
/// (`class`, `name`, `vector_type` and the `file_*` statistics are added).
pub struct Grid<'a, T> {
    pub name: &'a str,
    pub class: GridClass,
    /// For vector grids: how the vectors transform (`invariant`, `contravariant relative`, …).
    pub vector_type: Option<&'a str>,
    pub transform: Transform,
    pub leaves: &'a Leaves<T>,
    pub metadata: MetaMap,
}

/// A grid of either value type.
pub enum AnyGrid<'a> {
    Float(Grid<'a, f32>),
    Vec3(Grid<'a, [f32; 3]>),
}

/// Inclusive bounds of voxel indices: lowest and highest corner.
pub type IndexBounds = ([i32; 3], [i32; 3]);

/// Active voxels of `leaves`, and the bounds of their indices (none when empty).
pub fn active_stats<T: VoxelValue>(leaves: &Leaves<T>) -> (u64, Option<IndexBounds>) {
    let mut count = 0;
    let mut bounds: Option<IndexBounds> = None;
    for (origin, leaf) in leaves {
        for n in 0..512 {
            if !leaf.is_active(n) {
                continue;
            }
            count += 1;
            let p = [
                origin[0] + (n >> 6) as i32,
                origin[1] + ((n >> 3) & 7) as i32,
                origin[2] + (n & 7) as i32,
            ];
            bounds = Some(match bounds {
                None => (p, p),
                Some((lo, hi)) => (
                    [0, 1, 2].map(|a| lo[a].min(p[a])),
                    [0, 1, 2].map(|a| hi[a].max(p[a])),
                ),
            });
        }
    }
    (count, bounds)
}

/// The nodes above the leaves: upper origin → lower origin → leaf origins, all in order.
type Hierarchy = BTreeMap<[i32; 3], BTreeMap<[i32; 3], Vec<[i32; 3]>>>;

fn floor_to(v: i32, span: i32) -> i32 {
    v.div_euclid(span) * span
}

/// The offset of a child of origin `child` inside its parent of `span` voxels whose children
/// span `child_span` voxels (`InternalNode::coordToOffset`), with `dim` children an edge.
fn child_offset(child: [i32; 3], span: i32, child_span: i32, dim: i32) -> usize {
    let local = child.map(|c| c.rem_euclid(span) / child_span);
    ((local[0] * dim + local[1]) * dim + local[2]) as usize
}

fn hierarchy<T>(leaves: &Leaves<T>) -> Hierarchy {
    let mut tree: Hierarchy = BTreeMap::new();
    for &origin in leaves.keys() {
        let upper = origin.map(|c| floor_to(c, UPPER_SPAN));
        let lower = origin.map(|c| floor_to(c, LOWER_SPAN));
        tree.entry(upper)
            .or_default()
            .entry(lower)
            .or_default()
            .push(origin);
    }
    // Children in offset order (x slowest), as OpenVDB's child iterators visit them; inside
    // one parent that is also their coordinate order.
    for lowers in tree.values_mut() {
        for leaves in lowers.values_mut() {
            leaves.sort_by_key(|&o| child_offset(o, LOWER_SPAN, LEAF_DIM, LOWER_DIM));
        }
    }
    tree
}

/// A node mask of `bits` bits with the given offsets on.
fn mask_words(bits: usize, on: impl Iterator<Item = usize>) -> Vec<u64> {
    let mut words = vec![0u64; bits / 64];
    for n in on {
        words[n >> 6] |= 1 << (n & 63);
    }
    words
}

fn write_words(out: &mut Vec<u8>, words: &[u64]) {
    for w in words {
        out.extend_from_slice(&w.to_le_bytes());
    }
}

/// An internal node's topology: child mask, an empty value mask, and its (all background)
/// values, mask-compressed to none.
fn write_internal_topology(out: &mut Vec<u8>, values: usize, children: &[usize]) {
    write_words(out, &mask_words(values, children.iter().copied()));
    write_words(out, &vec![0u64; values / 64]);
    out.push(NO_MASK_OR_INACTIVE_VALS);
}

fn write_tree<T: VoxelValue>(out: &mut Vec<u8>, grid: &Grid<T>, block_pos: &mut u64) {
    let tree = hierarchy(grid.leaves);
    // Topology.
    out.extend_from_slice(&1i32.to_le_bytes());
    T::ZERO.write(out);
    out.extend_from_slice(&0u32.to_le_bytes());
    out.extend_from_slice(&(tree.len() as u32).to_le_bytes());
    for (upper, lowers) in &tree {
        for c in upper {
            out.extend_from_slice(&c.to_le_bytes());
        }
        let mut lower_offsets: Vec<([i32; 3], usize)> = lowers
            .keys()
            .map(|&o| (o, child_offset(o, UPPER_SPAN, LOWER_SPAN, UPPER_DIM)))
            .collect();
        lower_offsets.sort_by_key(|&(_, n)| n);
        let offsets: Vec<usize> = lower_offsets.iter().map(|&(_, n)| n).collect();
        write_internal_topology(out, 32 * 32 * 32, &offsets);
        for (lower, _) in &lower_offsets {
            let leaves = &lowers[lower];
            let offsets: Vec<usize> = leaves
                .iter()
                .map(|&o| child_offset(o, LOWER_SPAN, LEAF_DIM, LOWER_DIM))
                .collect();
            write_internal_topology(out, 16 * 16 * 16, &offsets);
            for origin in leaves {
                write_words(out, &grid.leaves[origin].mask);
            }
        }
    }
    // Buffers, in the same order.
    *block_pos = out.len() as u64;
    for lowers in tree.values() {
        let mut lower_offsets: Vec<([i32; 3], usize)> = lowers
            .keys()
            .map(|&o| (o, child_offset(o, UPPER_SPAN, LOWER_SPAN, UPPER_DIM)))
            .collect();
        lower_offsets.sort_by_key(|&(_, n)| n);
        for (lower, _) in &lower_offsets {
            for origin in &lowers[lower] {
                let leaf = &grid.leaves[origin];
                write_words(out, &leaf.mask);
                out.push(NO_MASK_OR_INACTIVE_VALS);
                for n in 0..512 {
                    if leaf.is_active(n) {
                        leaf.values[n].write(out);
                    }
                }
            }
        }
    }
}

/// The metadata OpenVDB writes with a grid: its own, then class, name, vector type and the
/// `file_*` statistics (bounds of the active voxels, their count, the compression, an
/// estimate of the grid's size in memory).
fn grid_metadata<T: VoxelValue>(grid: &Grid<T>) -> MetaMap {
    let mut meta = grid.metadata.clone();
    meta.insert("class".into(), Meta::String(grid.class.name().into()));
    meta.insert("name".into(), Meta::String(grid.name.into()));
    meta.insert("is_local_space".into(), Meta::Bool(false));
    meta.insert("is_saved_as_half_float".into(), Meta::Bool(false));
    if let Some(v) = grid.vector_type {
        meta.insert("vector_type".into(), Meta::String(v.into()));
    }
    let (count, bounds) = active_stats(grid.leaves);
    let (lo, hi) = bounds.unwrap_or(([0; 3], [0; 3]));
    meta.insert("file_bbox_min".into(), Meta::Vec3i(lo));
    meta.insert("file_bbox_max".into(), Meta::Vec3i(hi));
    meta.insert("file_voxel_count".into(), Meta::Int64(count as i64));
    meta.insert(
        "file_compression".into(),
        Meta::String("active values".into()),
    );
    let tree = hierarchy(grid.leaves);
    // In u64: in WebAssembly usize has 32 bits, and a sparse grid of many nodes passes 2^32.
    let lowers: u64 = tree.values().map(|l| l.len() as u64).sum();
    let value = std::mem::size_of::<T>() as u64;
    let bytes = grid.leaves.len() as u64 * (512 * value + 64 + 16)
        + lowers * (4096 * (value.max(8)) + 2 * 512 + 16)
        + tree.len() as u64 * (32768 * (value.max(8)) + 2 * 4096 + 16);
    meta.insert("file_mem_bytes".into(), Meta::Int64(bytes as i64));
    meta
}

fn write_grid<T: VoxelValue>(out: &mut Vec<u8>, grid: &Grid<T>) {
    write_string(out, grid.name);
    write_string(out, &format!("Tree_{}_5_4_3", T::TYPE_NAME));
    write_string(out, "");
    // Positions are absolute in the file: `out` is what follows the header.
    let absolute = |at: usize| (HEADER_LEN + at) as u64;
    let positions_at = out.len();
    out.extend_from_slice(&[0u8; 24]);
    let grid_pos = absolute(out.len());
    out.extend_from_slice(&COMPRESS_ACTIVE_MASK.to_le_bytes());
    write_meta(out, &grid_metadata(grid));
    grid.transform.write(out);
    let mut block_at = 0;
    write_tree(out, grid, &mut block_at);
    let (block_pos, end_pos) = (absolute(block_at as usize), absolute(out.len()));
    for (i, v) in [grid_pos, block_pos, end_pos].iter().enumerate() {
        let at = positions_at + 8 * i;
        out[at..at + 8].copy_from_slice(&v.to_le_bytes());
    }
}

/// A UUID-shaped identifier (36 ASCII characters) that depends on `bytes` only, so the same
/// grids give the same file (OpenVDB draws a random one; readers only compare them).
fn content_uuid(bytes: &[u8]) -> String {
    let fnv = |seed: u64| {
        bytes.iter().fold(seed, |h, &b| {
            (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
        })
    };
    let hex = format!(
        "{:016X}{:016X}",
        fnv(0xcbf2_9ce4_8422_2325),
        fnv(0x8422_2325_cbf2_9ce4)
    );
    format!(
        "{}-{}-{}-{}-{}",
        &hex[0..8],
        &hex[8..12],
        &hex[12..16],
        &hex[16..20],
        &hex[20..32]
    )
}

/// The length of the header before the file metadata: magic, versions, the offsets flag and
/// the UUID.
const HEADER_LEN: usize = 8 + 4 + 8 + 1 + 36;

/// The bytes of a `.vdb` file holding `grids` (names should differ) and the file-level
/// metadata `file_meta`.
pub fn write(grids: &[AnyGrid], file_meta: &MetaMap) -> Vec<u8> {
    let mut body = Vec::new();
    write_meta(&mut body, file_meta);
    body.extend_from_slice(&(grids.len() as i32).to_le_bytes());
    for g in grids {
        match g {
            AnyGrid::Float(g) => write_grid(&mut body, g),
            AnyGrid::Vec3(g) => write_grid(&mut body, g),
        }
    }
    let mut out = Vec::with_capacity(HEADER_LEN + body.len());
    out.extend_from_slice(&MAGIC.to_le_bytes());
    out.extend_from_slice(&FILE_VERSION.to_le_bytes());
    out.extend_from_slice(&LIBRARY_VERSION.0.to_le_bytes());
    out.extend_from_slice(&LIBRARY_VERSION.1.to_le_bytes());
    out.push(1);
    out.extend_from_slice(content_uuid(&body).as_bytes());
    debug_assert_eq!(out.len(), HEADER_LEN);
    out.extend_from_slice(&body);
    out
}

/// Whether `bytes` is a whole `.vdb` file as [`write`] makes them: the magic, the version, and
/// grids whose end positions lie within the file, the last one at its end.
pub fn is_complete(bytes: &[u8]) -> bool {
    fn read<const N: usize>(b: &[u8], at: &mut usize) -> Option<[u8; N]> {
        let v = b.get(*at..*at + N)?.try_into().ok()?;
        *at += N;
        Some(v)
    }
    fn string(b: &[u8], at: &mut usize) -> Option<()> {
        let n = u32::from_le_bytes(read(b, at)?) as usize;
        b.get(*at..*at + n)?;
        *at += n;
        Some(())
    }
    let check = || -> Option<bool> {
        let mut at = 0;
        if i64::from_le_bytes(read(bytes, &mut at)?) != MAGIC {
            return Some(false);
        }
        if u32::from_le_bytes(read(bytes, &mut at)?) != FILE_VERSION {
            return Some(false);
        }
        at = HEADER_LEN;
        let count = u32::from_le_bytes(read(bytes, &mut at)?);
        for _ in 0..count {
            string(bytes, &mut at)?;
            string(bytes, &mut at)?;
            string(bytes, &mut at)?;
        }
        let grids = i32::from_le_bytes(read(bytes, &mut at)?);
        let mut end = at as u64;
        for _ in 0..grids {
            string(bytes, &mut at)?;
            string(bytes, &mut at)?;
            string(bytes, &mut at)?;
            let _grid = read::<8>(bytes, &mut at)?;
            let _block = read::<8>(bytes, &mut at)?;
            end = u64::from_le_bytes(read(bytes, &mut at)?);
            if end > bytes.len() as u64 {
                return Some(false);
            }
            at = end as usize;
        }
        Some(grids > 0 && end == bytes.len() as u64)
    };
    check().unwrap_or(false)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_follow_openvdb() {
        // LeafNode::coordToOffset: x slowest, z fastest.
        assert_eq!(leaf_offset(1, 0, 0), 64);
        assert_eq!(leaf_offset(0, 1, 0), 8);
        assert_eq!(leaf_offset(-1, -1, -1), 511);
        assert_eq!(leaf_origin(-1, 8, 15), [-8, 8, 8]);
        assert_eq!(
            child_offset([8, 0, 16], LOWER_SPAN, LEAF_DIM, LOWER_DIM),
            256 + 2
        );
        assert_eq!(
            child_offset([-128, 0, 0], UPPER_SPAN, LOWER_SPAN, UPPER_DIM),
            31 * 1024
        );
    }

    #[test]
    fn a_file_is_complete_only_whole() {
        let mut leaves: Leaves<f32> = BTreeMap::new();
        let mut leaf = Leaf::new();
        leaf.values[3] = 2.5;
        leaf.set_active(3, true);
        leaves.insert([0, 0, -8], leaf);
        let grid = Grid {
            name: "density",
            class: GridClass::FogVolume,
            vector_type: None,
            transform: Transform::uniform(0.01),
            leaves: &leaves,
            metadata: MetaMap::new(),
        };
        let mut meta = MetaMap::new();
        meta.insert("creator".into(), Meta::String("a test".into()));
        meta.insert("windfield_time".into(), Meta::Double(1.5));
        let bytes = write(&[AnyGrid::Float(grid)], &meta);
        assert!(is_complete(&bytes));
        assert!(!is_complete(&bytes[..bytes.len() - 1]));
        assert_eq!(&bytes[..4], &[0x20, 0x42, 0x44, 0x56]);
        assert_eq!(active_stats(&leaves), (1, Some(([0, 0, -5], [0, 0, -5]))));
    }
}

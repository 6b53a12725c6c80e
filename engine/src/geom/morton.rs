//! Morton (Z-order) codes: the bits of the cell indices interleaved, so
//! cells close in space get close codes (hashed grids read nearby memory).

/// The bits of `v` moved to every second position of a `u64`.
#[inline]
fn spread2(v: u32) -> u64 {
    let mut x = u64::from(v);
    x = (x | (x << 16)) & 0x0000_FFFF_0000_FFFF;
    x = (x | (x << 8)) & 0x00FF_00FF_00FF_00FF;
    x = (x | (x << 4)) & 0x0F0F_0F0F_0F0F_0F0F;
    x = (x | (x << 2)) & 0x3333_3333_3333_3333;
    (x | (x << 1)) & 0x5555_5555_5555_5555
}

/// The low 21 bits of `v` moved to every third position of a `u64`.
#[inline]
fn spread3(v: u32) -> u64 {
    let mut x = u64::from(v) & 0x1F_FFFF;
    x = (x | (x << 32)) & 0x001F_0000_0000_FFFF;
    x = (x | (x << 16)) & 0x001F_0000_FF00_00FF;
    x = (x | (x << 8)) & 0x100F_00F0_0F00_F00F;
    x = (x | (x << 4)) & 0x10C3_0C30_C30C_30C3;
    (x | (x << 2)) & 0x1249_2492_4924_9249
}

/// Morton code of grid cell `cell` (indices taken modulo 2^32 in 2D, 2^21
/// in 3D: far cells may share a code, which a hashed grid tolerates).
#[inline]
pub fn encode<const D: usize>(cell: [i64; D]) -> u64 {
    match D {
        1 => u64::from(cell[0] as u32),
        2 => spread2(cell[0] as u32) | (spread2(cell[1] as u32) << 1),
        3 => {
            spread3(cell[0] as u32)
                | (spread3(cell[1] as u32) << 1)
                | (spread3(cell[2] as u32) << 2)
        }
        _ => unreachable!("Morton codes of dimension {D}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn morton_interleaves_bits() {
        assert_eq!(encode([0b11, 0b00]), 0b0101);
        assert_eq!(encode([0b00, 0b11]), 0b1010);
        assert_eq!(encode([1, 0, 0]), 1);
        assert_eq!(encode([0, 1, 0]), 2);
        assert_eq!(encode([0, 0, 1]), 4);
        assert_eq!(encode([3, 3, 3]), 63);
        // the top kept bit lands at position 62 in 3D
        assert_eq!(encode([0, 0, 1 << 20]), 1 << 62);
        // every bit of a random index survives (decode by hand)
        let i = 0x1A_2B3Cu32 as i64;
        let c = encode([i, 0, 0]);
        let mut back = 0u64;
        for b in 0..21 {
            back |= ((c >> (3 * b)) & 1) << b;
        }
        assert_eq!(back as i64, i);
    }
}

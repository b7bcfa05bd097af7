//! The circuit: typed nets joined by components of the component library
//! (docs/netlist.md), and the one definition of what each component
//! computes in a cycle ([`eval`]), used both by the translation (constant
//! folding) and by the simulator, so a folded constant is exactly what the
//! component would have computed.
//!
//! A net has one driver (one output pin of one component) and an
//! elementary type. Components are stored in an order where every
//! combinational input is driven by an earlier component or a register:
//! registers ([`Kind::Register`]) are the only components whose input may
//! come from later, which is what makes a circuit free of combinational
//! loops.

use stc_ir::FaultKind;
use stc_values::{BinOp, ElemType, Intrinsic, UnOp, Value};

/// A net, by its position in [`Circuit::nets`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub struct NetId(pub u32);

impl NetId {
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// What a component is (its entry in the component library).
#[derive(Clone, Debug, PartialEq)]
pub enum Kind {
    /// An input module: a value from outside the circuit (a program's
    /// VAR_INPUT, a `%I` variable), held until the environment changes it;
    /// `init` before it ever does. Output X1.
    Input {
        name: String,
        init: Value,
        /// Other paths of the same variable (a located variable's name).
        aliases: Vec<String>,
    },
    /// The task clock (TIME or LTIME): the time of the cycle. Output X1.
    Clock,
    /// A constant. Output X1.
    Const(Value),
    /// A unit delay: X1 is the value A1 had at the end of the previous
    /// cycle (`init` in the first). The state of the program.
    Register {
        name: String,
        init: Value,
        aliases: Vec<String>,
    },
    /// An output module: the value of A1 at the end of the cycle.
    Output { name: String },
    /// A run-time fault of the program: when A2 (BOOL, the statement is
    /// reached) is TRUE and A1 (USINT, a fault code of a component) is not
    /// 0, the cycle faults here.
    Fault {
        instance: String,
        pou: String,
        file: String,
        line: u32,
        col: u32,
    },
    /// A two-way selector: X1 = A1 ? A2 : A3.
    Switch,
    /// An indexed selector (a multiplexer tree): X1 = A(2 + (S - lo)) of
    /// the data inputs A2..An, the type's default when S is outside them.
    Index { lo: i128 },
    /// A range check: X1 = A1; F1 = the fault's code when A1 is outside
    /// `lo..=hi`, else 0.
    Range {
        lo: i128,
        hi: i128,
        fault: FaultKind,
    },
    /// A binary operator of `stc_values` on A1 and A2.
    Binary(BinOp),
    /// A unary operator on A1.
    Unary(UnOp),
    /// A conversion from A1's type to X1's.
    Convert,
    /// A standard function of `stc_values` on A1..An.
    Call(Intrinsic),
    /// A part of a bit string (`x.3`, `w.%B1`): X1 is the `bits` bits of A1
    /// from bit `pos · bits` up (a BOOL when `bits` is 1).
    PartGet { bits: u32, pos: u32 },
    /// The bit string A1 with that part replaced by A2 (the assignment
    /// `x.3 := b`, `w.%B1 := v`).
    PartSet { bits: u32, pos: u32 },
}

impl Kind {
    /// Whether two components of this kind with the same inputs compute the
    /// same value (and may therefore be shared).
    pub fn is_pure(&self) -> bool {
        !matches!(
            self,
            Kind::Input { .. } | Kind::Register { .. } | Kind::Output { .. } | Kind::Fault { .. }
        )
    }
}

/// The input pins of a component: held inline up to three (almost every
/// component), so that a component costs no allocation of its own.
pub type Pins = smallvec::SmallVec<[NetId; 3]>;
/// The output pins: X1, and F1 for a component that may fault.
pub type Outs = smallvec::SmallVec<[NetId; 2]>;

#[derive(Clone, Debug, PartialEq)]
pub struct Component {
    pub kind: Kind,
    pub inputs: Pins,
    /// X1, then F1 (the fault code, USINT) for a component that may fault.
    pub outputs: Outs,
}

/// A whole circuit.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Circuit {
    /// The program it computes (the document's `FileName`).
    pub name: String,
    /// The type of each net.
    pub nets: Vec<ElemType>,
    pub components: Vec<Component>,
}

impl Circuit {
    /// How many components of each library name the circuit has, sorted.
    pub fn census(&self) -> Vec<(&'static str, usize)> {
        let mut map = std::collections::BTreeMap::new();
        for c in &self.components {
            *map.entry(crate::library::name_of(&c.kind)).or_insert(0) += 1;
        }
        map.into_iter().collect()
    }
}

/// The value a net of type `t` holds when nothing defines it otherwise.
pub fn default_of(t: ElemType) -> Value {
    stc_values::default_value(t)
}

/// What a combinational component computes: its X1 value and its fault
/// (F1), from the values and types of its inputs. A faulting operation
/// gives the type's default value (X1 of a range check passes A1 through).
/// Sources, registers, outputs and fault modules are not evaluated here.
pub fn eval(
    kind: &Kind,
    in_tys: &[ElemType],
    ins: &[Value],
    out_ty: ElemType,
) -> (Value, Option<FaultKind>) {
    let lift = |r: Result<stc_values::Outcome, stc_values::Fault>| match r {
        Ok(o) => (o.value, None),
        Err(f) => (default_of(out_ty), Some(FaultKind::from_value_fault(f))),
    };
    match kind {
        Kind::Switch => match ins {
            [Value::Bool(c), a, b] => (if *c { a.clone() } else { b.clone() }, None),
            _ => (default_of(out_ty), Some(FaultKind::InvalidCode)),
        },
        Kind::Index { lo } => {
            let Some(i) = ins.first().and_then(Value::as_int) else {
                return (default_of(out_ty), Some(FaultKind::InvalidCode));
            };
            let data = &ins[1..];
            let k = i.checked_sub(*lo).and_then(|k| usize::try_from(k).ok());
            match k.and_then(|k| data.get(k)) {
                Some(v) => (v.clone(), None),
                None => (default_of(out_ty), None),
            }
        }
        Kind::Range { lo, hi, fault } => {
            let Some(v) = ins.first() else {
                return (default_of(out_ty), Some(FaultKind::InvalidCode));
            };
            let inside = v.as_int().is_some_and(|i| *lo <= i && i <= *hi);
            (v.clone(), (!inside).then_some(*fault))
        }
        Kind::Binary(op) => match (ins, in_tys) {
            ([a, b], [ta, tb]) => lift(stc_values::binary(*op, *ta, a, *tb, b, out_ty)),
            _ => (default_of(out_ty), Some(FaultKind::InvalidCode)),
        },
        Kind::Unary(op) => match (ins, in_tys) {
            ([a], [ta]) => lift(stc_values::unary(*op, *ta, a)),
            _ => (default_of(out_ty), Some(FaultKind::InvalidCode)),
        },
        Kind::Convert => match (ins, in_tys) {
            ([a], [ta]) if *ta == out_ty => (a.clone(), None),
            ([a], [ta]) => match stc_values::convert(*ta, out_ty, a) {
                Ok(v) => (v, None),
                Err(f) => (default_of(out_ty), Some(FaultKind::from_value_fault(f))),
            },
            _ => (default_of(out_ty), Some(FaultKind::InvalidCode)),
        },
        Kind::Call(f) => lift(stc_values::call(*f, in_tys, ins, out_ty)),
        Kind::PartGet { bits, pos } => match ins {
            [w] => match w.as_int() {
                Some(w) => (part_get(w, *bits, *pos, out_ty), None),
                None => (default_of(out_ty), Some(FaultKind::InvalidCode)),
            },
            _ => (default_of(out_ty), Some(FaultKind::InvalidCode)),
        },
        Kind::PartSet { bits, pos } => match ins {
            [w, v] => {
                let v = match v {
                    Value::Bool(b) => Some(i128::from(*b)),
                    v => v.as_int(),
                };
                match (w.as_int(), v) {
                    (Some(w), Some(v)) => (part_set(w, v, *bits, *pos, out_ty), None),
                    _ => (default_of(out_ty), Some(FaultKind::InvalidCode)),
                }
            }
            _ => (default_of(out_ty), Some(FaultKind::InvalidCode)),
        },
        Kind::Input { .. }
        | Kind::Clock
        | Kind::Const(_)
        | Kind::Register { .. }
        | Kind::Output { .. }
        | Kind::Fault { .. } => (default_of(out_ty), Some(FaultKind::InvalidCode)),
    }
}

/// The mask of a part of `bits` bits (at most 64).
fn part_mask(bits: u32) -> u128 {
    if bits >= 64 {
        u128::from(u64::MAX)
    } else {
        (1u128 << bits) - 1
    }
}

/// Bits `pos · bits ..` of the word `w`, as a value of type `t`.
fn part_get(w: i128, bits: u32, pos: u32, t: ElemType) -> Value {
    let shift = bits.saturating_mul(pos).min(127);
    let raw = ((w as u128) >> shift) & part_mask(bits);
    if t == ElemType::Bool {
        Value::Bool(raw != 0)
    } else {
        Value::Int(stc_values::wrap(t, raw as i128))
    }
}

/// The word `w` (of type `t`) with bits `pos · bits ..` replaced by `v`.
fn part_set(w: i128, v: i128, bits: u32, pos: u32, t: ElemType) -> Value {
    let shift = bits.saturating_mul(pos).min(127);
    let mask = part_mask(bits) << shift;
    let raw = ((w as u128) & !mask) | (((v as u128) << shift) & mask);
    Value::Int(stc_values::wrap(t, raw as i128))
}

/// Whether a component may fault on some input values (then it has an F1
/// pin). Errs towards a pin: an extra pin costs nothing, a missing one
/// would let a fault pass unseen.
pub fn may_fault(kind: &Kind, in_tys: &[ElemType], out_ty: ElemType) -> bool {
    use stc_values::is_time_like;
    let timeish = in_tys.iter().chain([&out_ty]).any(|t| is_time_like(*t));
    match kind {
        Kind::Range { .. } => true,
        Kind::Binary(op) => match op {
            BinOp::Div | BinOp::Mod | BinOp::Pow => true,
            BinOp::Add | BinOp::Sub | BinOp::Mul => timeish,
            _ => false,
        },
        Kind::Unary(_) => false,
        Kind::Convert => match in_tys {
            [from] => *from != out_ty && stc_values::conversion_may_fault(*from, out_ty),
            _ => true,
        },
        Kind::Call(f) => {
            use Intrinsic as I;
            match f {
                I::Abs
                | I::Sqrt
                | I::Ln
                | I::Log
                | I::Exp
                | I::Sin
                | I::Cos
                | I::Tan
                | I::Asin
                | I::Acos
                | I::Atan
                | I::Atan2
                | I::Shl
                | I::Shr
                | I::Rol
                | I::Ror
                | I::Sel
                | I::Max
                | I::Min
                | I::Limit
                | I::Move
                | I::And
                | I::Or
                | I::Xor
                | I::Not
                | I::Gt
                | I::Ge
                | I::Eq
                | I::Le
                | I::Lt
                | I::Ne => false,
                I::Add | I::Sub | I::Mul => timeish,
                _ => true,
            }
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn get(w: i128, bits: u32, pos: u32, t: ElemType) -> Value {
        let k = Kind::PartGet { bits, pos };
        eval(&k, &[ElemType::Lword], &[Value::Int(w)], t).0
    }

    fn set(w: i128, v: Value, bits: u32, pos: u32, t: ElemType) -> Value {
        let k = Kind::PartSet { bits, pos };
        eval(&k, &[t, ElemType::Bool], &[Value::Int(w), v], t).0
    }

    #[test]
    fn parts_of_bit_strings_are_read_and_replaced() {
        assert_eq!(get(0x00F0, 1, 4, ElemType::Bool), Value::Bool(true));
        assert_eq!(get(0x00F0, 1, 3, ElemType::Bool), Value::Bool(false));
        assert_eq!(get(0xABCD, 8, 1, ElemType::Byte), Value::Int(0xAB));
        let top = 1i128 << 63;
        assert_eq!(get(top, 1, 63, ElemType::Bool), Value::Bool(true));
        assert_eq!(get(top | 5, 32, 0, ElemType::Dword), Value::Int(5));
        // A write keeps the other bits and takes the part's low bits.
        assert_eq!(
            set(0x00F0, Value::Bool(true), 1, 0, ElemType::Word),
            Value::Int(0x00F1)
        );
        assert_eq!(
            set(0xFFFF, Value::Int(0x1AB), 8, 1, ElemType::Word),
            Value::Int(0xABFF)
        );
        assert_eq!(
            set(0, Value::Bool(true), 1, 63, ElemType::Lword),
            Value::Int(top)
        );
        // A signed word stays in its type's range.
        assert_eq!(
            set(-1, Value::Bool(false), 1, 15, ElemType::Int),
            Value::Int(32767)
        );
        assert_eq!(
            set(0, Value::Bool(true), 1, 15, ElemType::Int),
            Value::Int(-32768)
        );
    }
}

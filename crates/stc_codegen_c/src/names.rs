//! C names for ST entities, and C literals for values.
//!
//! Every ST name gets a prefix by kind (`v_` variables, `m_` struct
//! members, `g<k>_` globals, `FB_` instance structs, `F_` function frames,
//! `P_` bodies, `I_` initialisers, `T<k>_` other types), so no ST name can
//! be a C keyword, a library name or a macro, and names of different kinds
//! never meet. ST names are case-insensitive: one symbol gets one spelling
//! (the module's), so `Valve` and `VALVE` are the same C name and names that
//! differ in more than case stay different. Hidden variables are named by
//! their index (`h<k>_`), since their ST names carry a `$`.

use stc_ir::{Module, Var};
use stc_sema::{GlobalId, PouId, TypeId, TypeKind, VarId};
use stc_syntax::literal::DirectAddress;
use stc_syntax::token::ElemType;
use stc_values::Value;

/// An ST identifier as a C identifier fragment (ST identifiers are already
/// letters, digits and single underscores).
pub fn ident(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The C name of a variable of a POU (instance member or frame member).
pub fn var_name(m: &Module, index: VarId, v: &Var) -> String {
    if v.hidden.is_some() {
        format!("h{index}_{}", v.hidden.unwrap_or("x"))
    } else {
        format!("v_{}", ident(m.spelled(v.name, v.span)))
    }
}

/// The C type of an elementary type.
pub fn elem_c(e: ElemType) -> &'static str {
    use ElemType as E;
    match e {
        E::Bool | E::Usint | E::Byte | E::Char => "uint8_t",
        E::Sint => "int8_t",
        E::Int => "int16_t",
        E::Dint => "int32_t",
        E::Lint | E::Time | E::Ltime | E::Date | E::Ldate | E::Tod | E::Ltod | E::Dt | E::Ldt => {
            "int64_t"
        }
        E::Uint | E::Word | E::Wchar => "uint16_t",
        E::Udint | E::Dword => "uint32_t",
        E::Ulint | E::Lword => "uint64_t",
        E::Real => "float",
        E::Lreal => "double",
        E::String => "uint8_t",
        E::Wstring => "uint16_t",
    }
}

/// The `STC_E_*` code of an elementary type (`ElemType::code`, written
/// into `stc_codes.h`).
pub fn elem_code(e: ElemType) -> u32 {
    u32::from(e.code())
}

/// The C name of a type (a typedef for strings, arrays, structs and
/// instances; the stdint type of scalars).
pub fn type_name(m: &Module, t: TypeId) -> String {
    match m.types.kind(t) {
        TypeKind::Elem(e) => elem_c(*e).to_string(),
        TypeKind::Subrange { base, .. } | TypeKind::Enum { base, .. } => elem_c(*base).to_string(),
        TypeKind::String { wide: false, len } => format!("stc_str_{len}"),
        TypeKind::String { wide: true, len } => format!("stc_wstr_{len}"),
        TypeKind::Array { dims, elem } => {
            // Structural: arrays of the same shape are one C type, as they
            // are one ST type (assignable to each other).
            let mut n = format!("A_{}", type_name(m, *elem).replace(' ', "_"));
            for (l, h) in dims {
                let b = |x: i128| {
                    if x < 0 {
                        format!("m{}", -x)
                    } else {
                        x.to_string()
                    }
                };
                n.push_str(&format!("_{}_{}", b(*l), b(*h)));
            }
            n
        }
        TypeKind::Struct { .. } => match m.type_name(t) {
            Some(n) => format!("S{}_{}", t.0, ident(n)),
            None => format!("S{}", t.0),
        },
        TypeKind::Fb(p) | TypeKind::Program(p) => pou_type_name(m, *p),
        TypeKind::Error | TypeKind::Void => "uint8_t".to_string(),
        TypeKind::Ref(_) | TypeKind::Ptr(_) => "stc_ref".to_string(),
    }
}

/// The instance struct of a function block or program.
pub fn pou_type_name(m: &Module, p: PouId) -> String {
    let pou = &m.pous[p];
    format!("FB{p}_{}", ident(m.spelled(pou.name, pou.name_span)))
}

/// The frame struct of a function.
pub fn frame_type_name(m: &Module, p: PouId) -> String {
    let pou = &m.pous[p];
    format!("F{p}_{}", ident(m.spelled(pou.name, pou.name_span)))
}

/// The body function of a POU.
pub fn body_name(m: &Module, p: PouId) -> String {
    let pou = &m.pous[p];
    format!("P{p}_{}", ident(m.spelled(pou.name, pou.name_span)))
}

/// The initialiser of a POU's instance.
pub fn init_name(m: &Module, p: PouId) -> String {
    let pou = &m.pous[p];
    format!("I{p}_{}", ident(m.spelled(pou.name, pou.name_span)))
}

/// The C variable of a global.
pub fn global_name(m: &Module, g: GlobalId) -> String {
    let gl = &m.globals[g];
    format!("g{g}_{}", ident(m.spelled(gl.name, gl.span)))
}

/// The C variable of a process-image slot (`%QX0.1` → `io_QX0_1`).
pub fn io_name(a: &DirectAddress) -> String {
    format!(
        "io_{}",
        ident(&a.to_string().replace('%', "").replace('.', "_"))
    )
}

/// A C literal of a scalar value of elementary type `e` (typed, so that
/// the C expression has exactly the C type of `e`).
pub fn literal(e: ElemType, v: &Value) -> String {
    use ElemType as E;
    let int = match v {
        Value::Int(i) => *i,
        Value::Bool(b) => *b as i128,
        _ => 0,
    };
    match e {
        E::Real => {
            let x = v.as_real().unwrap_or(0.0) as f32;
            float_lit(x as f64, true)
        }
        E::Lreal => float_lit(v.as_real().unwrap_or(0.0), false),
        E::String | E::Wstring => "0U".to_string(),
        _ => {
            let c = elem_c(e);
            match c {
                // Suffixed literals, not INT64_C/UINT64_C (MISRA rule 7.2
                // checkers cannot see a `U` inside a macro).
                "int64_t" => {
                    if int == i64::MIN as i128 {
                        "((int64_t)(-9223372036854775807LL - 1LL))".to_string()
                    } else {
                        format!("((int64_t){int}LL)")
                    }
                }
                "uint64_t" => format!("((uint64_t){}ULL)", int as u64),
                "int32_t" => {
                    if int == i32::MIN as i128 {
                        "((int32_t)(-2147483647 - 1))".to_string()
                    } else {
                        format!("((int32_t){int})")
                    }
                }
                "int16_t" | "int8_t" => format!("(({c}){int})"),
                _ => format!("(({c}){}U)", int as u64),
            }
        }
    }
}

/// A C floating-point literal that reads back as exactly `x`.
fn float_lit(x: f64, single: bool) -> String {
    let suffix = if single { "F" } else { "" };
    if x.is_nan() {
        return if single {
            "((float)NAN)"
        } else {
            "((double)NAN)"
        }
        .to_string();
    }
    if x.is_infinite() {
        let s = if x > 0.0 { "" } else { "-" };
        return if single {
            format!("({s}HUGE_VALF)")
        } else {
            format!("({s}HUGE_VAL)")
        };
    }
    // `{:e}` is the shortest text that reads back as the same value.
    let text = if single {
        format!("{:e}", x as f32)
    } else {
        format!("{x:e}")
    };
    let (mant, exp) = text.split_once('e').unwrap_or((&text, "0"));
    let mant = if mant.contains('.') {
        mant.to_string()
    } else {
        format!("{mant}.0")
    };
    format!("({mant}e{exp}{suffix})")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals_are_typed_and_exact() {
        assert_eq!(literal(ElemType::Int, &Value::Int(-5)), "((int16_t)-5)");
        assert_eq!(literal(ElemType::Udint, &Value::Int(7)), "((uint32_t)7U)");
        assert_eq!(
            literal(ElemType::Lint, &Value::Int(i64::MIN as i128)),
            "((int64_t)(-9223372036854775807LL - 1LL))"
        );
        assert_eq!(literal(ElemType::Bool, &Value::Bool(true)), "((uint8_t)1U)");
        assert_eq!(literal(ElemType::Lreal, &Value::Real(0.1)), "(1.0e-1)");
        assert_eq!(literal(ElemType::Real, &Value::Real(1.5)), "(1.5e0F)");
        assert_eq!(literal(ElemType::Lreal, &Value::Real(-2.0)), "(-2.0e0)");
    }

    #[test]
    fn names_keep_to_c_identifiers() {
        assert_eq!(ident("Valve_2"), "Valve_2");
        assert_eq!(
            io_name(&stc_syntax::literal::parse_address("%QX0.1").unwrap()),
            "io_QX0_1"
        );
    }
}

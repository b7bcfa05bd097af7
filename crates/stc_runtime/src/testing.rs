//! A hand-made image for the unit tests: descriptors of every kind of
//! type and a configuration with three tasks (`fast` 10 ms priority 2 runs
//! `main`, `slow` 30 ms priority 1 runs nothing, `ev` SINGLE := trig runs
//! `p2`; `p3` has no task). `p2` has `inp := g` and `n => top`, `p3` has
//! `inp := g_sint` (a conversion). The bodies are hand-written bytecode:
//! `Other` only returns, `Main` faults with a division by zero (at
//! main.st:7:3) when its `flag` is TRUE, so the runtime is tested without
//! the bytecode compiler.
//!
//! Data area (absolute addresses):
//!
//! | address | what |
//! | --- | --- |
//! | 0 | `g : INT` (configuration Plant) |
//! | 2 | `K : INT` CONSTANT, initial value 5 |
//! | 4 | `lamp AT %QX0.0 : BOOL` (its process image slot) |
//! | 5 | `trig : BOOL` |
//! | 6 | `top : INT` (a top-level global list) |
//! | 8 | `g_sint : SINT` |
//! | 16 | instance `main` of `Main` (136 bytes) |
//! | 152 | instance `p2` of `Other` (4 bytes) |
//! | 156 | instance `p3` of `Other` (4 bytes) |
//! | 160 | slot `%QX1.0` (`Main.lamp_local`) |
//! | 161 | slot `%IX0.0` (`Main.sensor`) |

use stc_syntax::literal::{parse_address, DirectAddress};
use stc_syntax::token::ElemType;
use std::sync::Arc;

use stc_vm::image::*;
use stc_vm::instr::{Instr, Op, Tgt};

pub const T_BOOL: TypeRef = 0;
pub const T_INT: TypeRef = 1;
pub const T_REAL: TypeRef = 2;
pub const T_TIME: TypeRef = 3;
pub const T_STRING: TypeRef = 4;
pub const T_COLOR: TypeRef = 5;
pub const T_ARR: TypeRef = 6;
pub const T_MAT: TypeRef = 7;
pub const T_POINT: TypeRef = 8;
pub const T_TIMER: TypeRef = 9;
pub const T_MAIN: TypeRef = 10;
pub const T_LREAL: TypeRef = 11;
pub const T_SINT: TypeRef = 12;
pub const T_PTS: TypeRef = 13;
pub const T_OTHER: TypeRef = 14;
pub const T_WSTRING: TypeRef = 15;

pub const MAIN_AT: u32 = 16;
pub const P2_AT: u32 = 152;
pub const P3_AT: u32 = 156;

pub fn addr(text: &str) -> DirectAddress {
    parse_address(text).expect("a valid address")
}

fn var(name: &str, ty: TypeRef, kind: VarKind, offset: u32) -> VarDesc {
    VarDesc {
        name: name.into(),
        ty,
        kind,
        offset,
        in_frame: kind == VarKind::Temp,
        is_ref: false,
        location: None,
        constant: false,
        retain: false,
    }
}

fn located(name: &str, ty: TypeRef, offset: u32, at: &str) -> VarDesc {
    VarDesc {
        location: Some(addr(at)),
        ..reference(name, ty, VarKind::Var, offset)
    }
}

fn reference(name: &str, ty: TypeRef, kind: VarKind, offset: u32) -> VarDesc {
    VarDesc {
        is_ref: true,
        ..var(name, ty, kind, offset)
    }
}

fn pou(name: &str, kind: PouKind, size: u32, vars: Vec<VarDesc>, ty: TypeRef) -> PouDesc {
    PouDesc {
        name: name.into(),
        kind,
        instance_size: size,
        vars,
        instance_type: ty,
    }
}

/// The code of a POU starting at `entry`.
fn code(entry: u32) -> PouCode {
    PouCode {
        entry,
        frame_size: 8,
        frame_init_at: 0,
        frame_template: (0, 0),
    }
}

fn global(name: &str, ty: TypeRef, offset: u32, config: Option<u32>) -> GlobalDesc {
    GlobalDesc {
        name: name.into(),
        ty,
        offset,
        config,
        location: None,
        constant: false,
        retain: false,
    }
}

pub fn inst(name: &str, pou: u32, offset: u32, task: Option<u32>) -> ProgramInst {
    ProgramInst {
        name: name.into(),
        pou,
        offset,
        task,
        inputs: Vec::new(),
        outputs: Vec::new(),
    }
}

pub fn task(name: &str, interval_ms: Option<i64>, priority: u32) -> TaskDesc {
    TaskDesc {
        name: name.into(),
        interval_ns: interval_ms.map(|ms| ms * 1_000_000),
        priority,
        single: None,
    }
}

/// An image with no configuration and no program.
pub fn empty() -> Image {
    Image {
        code: vec![
            Instr::Ret {},
            Instr::Jz {
                c: Op::this(2),
                t: Tgt(3),
            },
            Instr::Fault {
                kind: u32::from(stc_ir::FaultKind::DivisionByZero.code()),
            },
            Instr::Ret {},
        ],
        consts: Vec::new(),
        data_size: 0,
        init: Vec::new(),
        stack_size: 64,
        model: Arc::new(Model::default()),
        pous: Vec::new(),
        calls: Vec::new(),
        elems: Vec::new(),
        lines: Vec::new(),
        files: Vec::new(),
    }
}

pub fn sample() -> Image {
    use ElemType as E;
    use VarKind as K;
    let types = vec![
        TypeDesc::Scalar(E::Bool),
        TypeDesc::Scalar(E::Int),
        TypeDesc::Scalar(E::Real),
        TypeDesc::Scalar(E::Time),
        TypeDesc::String {
            wide: false,
            cap: 10,
        },
        TypeDesc::Enum {
            name: "Color".into(),
            base: E::Int,
            values: vec![("Red".into(), 0), ("Green".into(), 1), ("Blue".into(), 2)],
        },
        TypeDesc::Array {
            elem: T_INT,
            dims: vec![(1, 3)],
            stride: 2,
        },
        TypeDesc::Array {
            elem: T_INT,
            dims: vec![(1, 2), (1, 3)],
            stride: 2,
        },
        TypeDesc::Struct {
            name: Some("Point".into()),
            fields: vec![
                FieldDesc {
                    name: "x".into(),
                    ty: T_INT,
                    offset: 0,
                },
                FieldDesc {
                    name: "y".into(),
                    ty: T_INT,
                    offset: 2,
                },
            ],
        },
        TypeDesc::Instance { pou: 0 },
        TypeDesc::Instance { pou: 1 },
        TypeDesc::Scalar(E::Lreal),
        TypeDesc::Scalar(E::Sint),
        TypeDesc::Array {
            elem: T_POINT,
            dims: vec![(0, 1)],
            stride: 4,
        },
        TypeDesc::Instance { pou: 2 },
        TypeDesc::String { wide: true, cap: 4 },
    ];
    let timer = pou(
        "Timer",
        PouKind::FunctionBlock,
        48,
        vec![
            var("IN", T_BOOL, K::Input, 0),
            var("PT", T_TIME, K::Input, 8),
            var("Q", T_BOOL, K::Output, 16),
            var("ET", T_TIME, K::Output, 24),
            var("start", T_TIME, K::Var, 32),
            var("edge", T_BOOL, K::Hidden, 40),
        ],
        T_TIMER,
    );
    let main = pou(
        "Main",
        PouKind::Program,
        136,
        vec![
            var("count", T_INT, K::Output, 0),
            var("flag", T_BOOL, K::Var, 2),
            var("tmp", T_INT, K::Temp, 0),
            var("tmr", T_TIMER, K::Var, 8),
            var("arr", T_ARR, K::Var, 56),
            var("m", T_MAT, K::Var, 62),
            var("pt", T_POINT, K::Var, 74),
            var("name", T_STRING, K::Var, 78),
            var("color", T_COLOR, K::Output, 90),
            reference("g_ext", T_INT, K::External, 92),
            located("lamp_local", T_BOOL, 96, "%QX1.0"),
            located("sensor", T_BOOL, 100, "%IX0.0"),
            var("x", T_REAL, K::Output, 104),
            var("lx", T_LREAL, K::Var, 112),
            var("pts", T_PTS, K::Var, 120),
            var("_edge", T_BOOL, K::Hidden, 128),
            var("w", T_WSTRING, K::Var, 130),
        ],
        T_MAIN,
    );
    let other = pou(
        "Other",
        PouKind::Program,
        4,
        vec![
            var("n", T_INT, K::Output, 0),
            var("inp", T_INT, K::Input, 2),
        ],
        T_OTHER,
    );
    let globals = vec![
        global("g", T_INT, 0, Some(0)),
        GlobalDesc {
            constant: true,
            ..global("K", T_INT, 2, Some(0))
        },
        GlobalDesc {
            location: Some(addr("%QX0.0")),
            ..global("lamp", T_BOOL, 4, Some(0))
        },
        global("trig", T_BOOL, 5, Some(0)),
        global("top", T_INT, 6, None),
        global("g_sint", T_SINT, 8, Some(0)),
    ];
    let mut init = vec![0u8; 168];
    init[2] = 5;
    init[(MAIN_AT + 96) as usize..(MAIN_AT + 100) as usize].copy_from_slice(&160u32.to_le_bytes());
    init[(MAIN_AT + 100) as usize..(MAIN_AT + 104) as usize].copy_from_slice(&161u32.to_le_bytes());
    let mut p2 = inst("p2", 2, P2_AT, Some(2));
    p2.inputs.push((
        2,
        T_INT,
        Source::Addr {
            offset: 0,
            ty: T_INT,
        },
    ));
    p2.outputs.push((
        0,
        T_INT,
        Source::Addr {
            offset: 6,
            ty: T_INT,
        },
    ));
    let mut p3 = inst("p3", 2, P3_AT, None);
    p3.inputs.push((
        2,
        T_INT,
        Source::Addr {
            offset: 8,
            ty: T_SINT,
        },
    ));
    let mut ev = task("ev", None, 0);
    ev.single = Some(Source::Addr {
        offset: 5,
        ty: T_BOOL,
    });
    let model = Model {
        types,
        pous: vec![timer, main, other],
        globals,
        configs: vec![ConfigDesc {
            name: "Plant".into(),
            resources: vec![ResourceDesc {
                name: Some("Cpu".into()),
                tasks: vec![task("fast", Some(10), 2), task("slow", Some(30), 1), ev],
                programs: vec![inst("main", 1, MAIN_AT, Some(0)), p2, p3],
            }],
        }],
        programs: vec![
            inst("Main", 1, MAIN_AT, None),
            inst("Other", 2, P2_AT, None),
        ],
        io: vec![
            IoSlot {
                address: addr("%QX0.0"),
                offset: 4,
                ty: T_BOOL,
            },
            IoSlot {
                address: addr("%QX1.0"),
                offset: 160,
                ty: T_BOOL,
            },
            IoSlot {
                address: addr("%IX0.0"),
                offset: 161,
                ty: T_BOOL,
            },
        ],
    };
    Image {
        data_size: 168,
        init,
        model: Arc::new(model),
        pous: vec![code(0), code(1), code(0)],
        lines: vec![LineEntry {
            pc: 1,
            pou: 1,
            file: 0,
            line: 7,
            col: 3,
        }],
        files: vec!["main.st".into()],
        ..empty()
    }
}

/// The program model of [`sample`].
pub fn sample_model() -> Model {
    (*sample().model).clone()
}

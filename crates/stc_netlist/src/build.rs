//! Building a circuit: components are added through [`Builder`], which folds
//! constants (with [`crate::circuit::eval`], the simulator's own code),
//! simplifies the selectors and gates whose result one input decides, and
//! shares equal sub-circuits (a pure component with the same kind and the
//! same input nets is made once). [`Builder::finish`] removes every
//! component that drives nothing the circuit shows (an output, a register,
//! a fault) and renumbers the nets in order.

use rustc_hash::FxHashMap;
use stc_values::{BinOp, ElemType, Intrinsic, UnOp, Value};

use crate::circuit::{eval, may_fault, Circuit, Component, Kind, NetId, Outs, Pins};

/// The identity of a pure component, for sharing.
#[derive(Clone, PartialEq, Eq, Hash)]
enum Key {
    Switch,
    Index(i128),
    Range(i128, i128, u8),
    Binary(u8),
    Unary(u8),
    Convert,
    Call(Intrinsic),
    Clock,
    Part(bool, u32, u32),
}

/// A constant's identity (reals by their bits, so NaN is one constant).
#[derive(Clone, PartialEq, Eq, Hash)]
enum ConstKey {
    Bool(bool),
    Int(i128),
    Real(u64),
}

fn const_key(v: &Value) -> Option<ConstKey> {
    match v {
        Value::Bool(b) => Some(ConstKey::Bool(*b)),
        Value::Int(i) => Some(ConstKey::Int(*i)),
        Value::Real(x) => Some(ConstKey::Real(x.to_bits())),
        _ => None,
    }
}

fn key_of(k: &Kind) -> Option<Key> {
    Some(match k {
        Kind::Switch => Key::Switch,
        Kind::Index { lo } => Key::Index(*lo),
        Kind::Range { lo, hi, fault } => Key::Range(*lo, *hi, fault.code()),
        Kind::Binary(op) => Key::Binary(*op as u8),
        Kind::Unary(op) => Key::Unary(*op as u8),
        Kind::Convert => Key::Convert,
        Kind::Call(f) => Key::Call(*f),
        Kind::Clock => Key::Clock,
        Kind::PartGet { bits, pos } => Key::Part(false, *bits, *pos),
        Kind::PartSet { bits, pos } => Key::Part(true, *bits, *pos),
        _ => return None,
    })
}

/// A pure component: its kind, its inputs and its result type.
type MemoKey = (Key, [NetId; 3], ElemType);

#[derive(Default)]
pub struct Builder {
    pub c: Circuit,
    /// The constant value of each net that has one.
    known: Vec<Option<Value>>,
    memo: FxHashMap<MemoKey, (NetId, Option<NetId>)>,
    consts: FxHashMap<(ElemType, ConstKey), NetId>,
}

impl Builder {
    pub fn new(name: String) -> Builder {
        Builder {
            c: Circuit {
                name,
                ..Circuit::default()
            },
            ..Builder::default()
        }
    }

    pub fn ty(&self, n: NetId) -> ElemType {
        self.c.nets[n.index()]
    }

    /// The constant value of a net, if it has one.
    pub fn known(&self, n: NetId) -> Option<&Value> {
        self.known.get(n.index()).and_then(|v| v.as_ref())
    }

    pub fn components(&self) -> usize {
        self.c.components.len()
    }

    fn net(&mut self, t: ElemType, known: Option<Value>) -> NetId {
        let id = NetId(self.c.nets.len() as u32);
        self.c.nets.push(t);
        self.known.push(known);
        id
    }

    /// A component that is never shared (modules, registers, faults).
    pub fn add(&mut self, kind: Kind, inputs: &[NetId], out: Option<ElemType>) -> NetId {
        let mut outputs = Outs::new();
        if let Some(t) = out {
            outputs.push(self.net(t, None));
        }
        let inputs = Pins::from_slice(inputs);
        let first = outputs.first().copied().unwrap_or(NetId(u32::MAX));
        self.c.components.push(Component {
            kind,
            inputs,
            outputs,
        });
        first
    }

    /// The constant `v` of type `t` (one component per distinct constant).
    pub fn konst(&mut self, t: ElemType, v: Value) -> NetId {
        let key = const_key(&v).map(|k| (t, k));
        if let Some(n) = key.as_ref().and_then(|k| self.consts.get(k)) {
            return *n;
        }
        let n = self.net(t, Some(v.clone()));
        self.c.components.push(Component {
            kind: Kind::Const(v),
            inputs: Pins::new(),
            outputs: Outs::from_slice(&[n]),
        });
        if let Some(k) = key {
            self.consts.insert(k, n);
        }
        n
    }

    pub fn bool(&mut self, b: bool) -> NetId {
        self.konst(ElemType::Bool, Value::Bool(b))
    }

    fn is_const_bool(&self, n: NetId, b: bool) -> bool {
        matches!(self.known(n), Some(Value::Bool(x)) if *x == b)
    }

    /// A pure operation: folded when every input is a constant and it does
    /// not fault, shared with an equal one made before. Returns X1 and, for
    /// a component that may fault, F1.
    pub fn op(&mut self, kind: Kind, inputs: &[NetId], out: ElemType) -> (NetId, Option<NetId>) {
        let all_known = inputs.iter().all(|n| self.known(*n).is_some());
        if all_known && !matches!(kind, Kind::Clock) {
            let in_tys: smallvec::SmallVec<[ElemType; 4]> =
                inputs.iter().map(|n| self.ty(*n)).collect();
            let vals: Vec<Value> = inputs
                .iter()
                .filter_map(|n| self.known(*n).cloned())
                .collect();
            let (v, fault) = eval(&kind, &in_tys, &vals, out);
            if fault.is_none() {
                return (self.konst(out, v), None);
            }
        }
        // (Components with more than three inputs are not shared: rare,
        // and a key without allocation is worth more.)
        let key = match (key_of(&kind), inputs) {
            (Some(k), ins) if ins.len() <= 3 => {
                let mut arr = [NetId(u32::MAX); 3];
                arr[..ins.len()].copy_from_slice(ins);
                Some((k, arr, out))
            }
            _ => None,
        };
        if let Some(hit) = key.as_ref().and_then(|k| self.memo.get(k)) {
            return *hit;
        }
        let in_tys: smallvec::SmallVec<[ElemType; 4]> =
            inputs.iter().map(|n| self.ty(*n)).collect();
        let faults = may_fault(&kind, &in_tys, out);
        let x = self.net(out, None);
        let f = faults.then(|| self.net(ElemType::Usint, None));
        let mut outputs = Outs::new();
        outputs.push(x);
        outputs.extend(f);
        self.c.components.push(Component {
            kind,
            inputs: Pins::from_slice(inputs),
            outputs,
        });
        if let Some(k) = key {
            self.memo.insert(k, (x, f));
        }
        (x, f)
    }

    pub fn not(&mut self, a: NetId) -> NetId {
        self.op(Kind::Unary(UnOp::Not), &[a], ElemType::Bool).0
    }

    pub fn and(&mut self, a: NetId, b: NetId) -> NetId {
        if self.is_const_bool(a, true) || a == b {
            return b;
        }
        if self.is_const_bool(b, true) {
            return a;
        }
        if self.is_const_bool(a, false) || self.is_const_bool(b, false) {
            return self.bool(false);
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.op(Kind::Binary(BinOp::And), &[a, b], ElemType::Bool).0
    }

    pub fn or(&mut self, a: NetId, b: NetId) -> NetId {
        if self.is_const_bool(a, false) || a == b {
            return b;
        }
        if self.is_const_bool(b, false) {
            return a;
        }
        if self.is_const_bool(a, true) || self.is_const_bool(b, true) {
            return self.bool(true);
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.op(Kind::Binary(BinOp::Or), &[a, b], ElemType::Bool).0
    }

    /// `c ? a : b`.
    pub fn switch(&mut self, c: NetId, a: NetId, b: NetId) -> NetId {
        if a == b || self.is_const_bool(c, true) {
            return a;
        }
        if self.is_const_bool(c, false) {
            return b;
        }
        let t = self.ty(a);
        self.op(Kind::Switch, &[c, a, b], t).0
    }

    /// Removes the components that drive nothing an output, register or
    /// fault module reads, directly or not, and renumbers the nets in the
    /// order of their drivers.
    pub fn finish(self) -> Circuit {
        let c = self.c;
        let mut driver: Vec<usize> = vec![usize::MAX; c.nets.len()];
        for (i, comp) in c.components.iter().enumerate() {
            for o in &comp.outputs {
                driver[o.index()] = i;
            }
        }
        let mut live = vec![false; c.components.len()];
        let mut stack: Vec<usize> = c
            .components
            .iter()
            .enumerate()
            .filter(|(_, k)| {
                matches!(
                    k.kind,
                    Kind::Output { .. }
                        | Kind::Register { .. }
                        | Kind::Fault { .. }
                        | Kind::Input { .. }
                )
            })
            .map(|(i, _)| i)
            .collect();
        while let Some(i) = stack.pop() {
            if std::mem::replace(&mut live[i], true) {
                continue;
            }
            for n in &c.components[i].inputs {
                let d = driver[n.index()];
                if d != usize::MAX && !live[d] {
                    stack.push(d);
                }
            }
        }
        let mut renum: Vec<u32> = vec![u32::MAX; c.nets.len()];
        let mut nets = Vec::with_capacity(c.nets.len());
        // (Compacted in place: no second array of components.)
        let mut components = c.components;
        let mut kept = 0;
        for i in 0..components.len() {
            if !live[i] {
                continue;
            }
            for o in &components[i].outputs {
                renum[o.index()] = nets.len() as u32;
                nets.push(c.nets[o.index()]);
            }
            components.swap(kept, i);
            kept += 1;
        }
        components.truncate(kept);
        for comp in &mut components {
            for n in comp.inputs.iter_mut().chain(comp.outputs.iter_mut()) {
                *n = NetId(renum[n.index()]);
            }
        }
        Circuit {
            name: c.name,
            nets,
            components,
        }
    }
}

//! The frames of each POU and the order POUs are compiled in. The program
//! model (types, the data area with its initial bytes and bound
//! references, variable descriptors) is `stc_ir::model`'s, built once
//! before any body is compiled.

use super::*;

impl Compiler<'_> {
    // ----- types -------------------------------------------------------------

    /// The elementary type a value is handled as; a reference is its
    /// 4-byte address, handled as a UDINT (NULL is 0).
    pub(super) fn scalar(&self, t: TypeId) -> Option<ElemType> {
        match self.m.types.kind(t) {
            stc_sema::TypeKind::Ref(_) => Some(ElemType::Udint),
            _ => self.m.types.scalar(t),
        }
    }

    pub(super) fn num(&self, t: TypeId) -> Option<Num> {
        self.scalar(t).and_then(Num::of)
    }

    pub(super) fn size_of(&self, t: TypeId) -> u32 {
        self.l.of(t).size
    }

    // ----- POU variables and frames -------------------------------------------

    /// POUs in an order where every callee comes before its callers.
    pub(super) fn callee_order(&self) -> Vec<PouId> {
        let n = self.m.pous.len();
        let mut deps: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (i, p) in self.m.pous.iter().enumerate() {
            stc_ir::visit::calls(&p.body, &mut |c| deps[i].push(c.0 as usize));
        }
        let mut order = Vec::with_capacity(n);
        let mut state = vec![0u8; n];
        for start in 0..n {
            if state[start] != 0 {
                continue;
            }
            let mut stack = vec![(start, 0usize)];
            state[start] = 1;
            while let Some(&mut (v, ref mut i)) = stack.last_mut() {
                if *i < deps[v].len() {
                    let w = deps[v][*i];
                    *i += 1;
                    if state[w] == 0 {
                        state[w] = 1;
                        stack.push((w, 0));
                    }
                } else {
                    state[v] = 2;
                    order.push(PouId(v as u32));
                    stack.pop();
                }
            }
        }
        order
    }

    /// The deepest chain of frames any program can build.
    pub(super) fn stack_need(&self) -> u32 {
        // Frames nest inside their caller's frame (a call reserves its
        // callee's frame among its temporaries), so a program's own frame
        // size already covers its whole call tree.
        self.pous.iter().map(|p| p.frame_size).max().unwrap_or(0) + 64
    }

    pub(super) fn compile_pou(&mut self, p: PouId) -> Result<(), CompileError> {
        let m = self.m;
        let pou = &m.pous[p];
        self.cur = p;
        self.frame = Frame::default();
        let function = pou.kind == AstPouKind::Function;
        // Frame variables: a function's inputs and in-outs first (the caller
        // writes them, the frame template starts after them), then the rest;
        // then temporaries.
        let by_caller =
            |v: &stc_ir::Var| function && matches!(v.section, Section::Input | Section::InOut);
        let mut order: Vec<VarId> = pou
            .vars
            .ids()
            .filter(|&i| self.l.pous[p].in_frame[i])
            .collect();
        order.sort_by_key(|&i| if by_caller(&pou.vars[i]) { 0 } else { 1 });
        let mut init_at = 0;
        let frame_of = || format!("the frame of `{}`", m.spelled(pou.name, pou.name_span));
        let mut top: u64 = 0;
        for &i in &order {
            let v = &pou.vars[i];
            let lay = if v.storage == Storage::Ref {
                stc_ir::layout::Layout { size: 4, align: 4 }
            } else {
                self.l.of(v.ty)
            };
            let a = u64::from(lay.align.max(1));
            let off = top.div_ceil(a) * a;
            top = off + u64::from(lay.size);
            if top > MAX_SIZE {
                return Err(too_large(pou.name_span, frame_of(), top));
            }
            self.frame.var_off.insert(i, off as u32);
            if by_caller(v) {
                init_at = top as u32;
            }
        }
        self.frame.top = align_up(top as u32, 8);
        let vars_end = self.frame.top;
        self.frame.max = vars_end;
        // The template: initial values of the frame variables after `init_at`.
        let mut template = vec![0u8; (vars_end - init_at) as usize];
        for &i in &order {
            let v = &pou.vars[i];
            let off = self.frame.var_off[&i];
            if off < init_at || v.storage == Storage::Ref {
                continue;
            }
            let bytes = self
                .d
                .init_bytes(v.ty, v.init.as_ref())
                .map_err(model_error)?;
            let s = (off - init_at) as usize;
            template[s..s + bytes.len()].copy_from_slice(&bytes);
        }
        let template = self.const_bytes(&template, 8);
        let entry = self.code.len() as u32;
        let file = {
            let f = &pou.file;
            match self.files.iter().position(|x| x == f) {
                Some(i) => i as u32,
                None => {
                    self.files.push(f.clone());
                    (self.files.len() - 1) as u32
                }
            }
        };
        let _ = file;
        self.block(&pou.body)?;
        self.emit(Instr::Ret {});
        let size = align_up(self.frame.max, 8);
        let need = self.frame.overflow.unwrap_or(0).max(u64::from(size));
        if need > MAX_SIZE {
            return Err(too_large(
                pou.name_span,
                format!(
                    "{} with its temporaries and the frames of its calls",
                    frame_of()
                ),
                need,
            ));
        }
        self.frames[p] = Some(FrameInfo {
            var_off: self.frame.var_off.clone(),
            size,
        });
        let code = &mut self.pous[p.index()];
        code.entry = entry;
        code.frame_size = size;
        code.frame_init_at = init_at;
        code.frame_template = (template, vars_end - init_at);
        let vars = &mut self
            .d
            .model_mut()
            .pous
            .get_mut(p.index())
            .ok_or_else(|| internal("a POU without a model"))?
            .vars;
        for (i, d) in vars.iter_mut().enumerate() {
            if d.in_frame {
                d.offset = *self
                    .frame
                    .var_off
                    .get(&VarId::new(i))
                    .ok_or_else(|| internal("a frame variable without a place"))?;
            }
        }
        Ok(())
    }
}

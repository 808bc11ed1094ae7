//! The machine code of one loaded model: the one module of the generator
//! with `unsafe`. It owns the JIT memory (a Cranelift [`JITModule`]) and the
//! function pointers into it, and hands out only safe calls that check what
//! the pointers need: a [`Machine`] is called through a typed [`FnId`] with
//! arrays of the arity the function was compiled for, and the parameter
//! values must cover what it reads. The memory is freed when the `Machine`
//! is dropped, and no pointer leaves it, so none outlives the code.
#![allow(unsafe_code)]

use std::marker::PhantomData;

use cranelift_jit::JITModule;
use cranelift_module::FuncId;

/// The signature of every compiled function: `(params, args, out)`, three
/// pointers to `f64`s. It reads `params[..p]` and `args[..A]` and writes
/// `out[..O]`, nothing else (see `jit::walk`).
type Raw = unsafe extern "C" fn(*const f64, *const f64, *mut f64);

/// A compiled function of a [`Machine`] taking `A` arguments and returning
/// `O` values.
#[derive(Debug)]
pub struct FnId<const A: usize, const O: usize> {
    index: u32,
    _arity: PhantomData<([f64; A], [f64; O])>,
}

impl<const A: usize, const O: usize> Clone for FnId<A, O> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<const A: usize, const O: usize> Copy for FnId<A, O> {}

/// One function's entry point and the arity it was compiled with.
struct Entry {
    code: Option<Raw>,
    args: usize,
    outs: usize,
}

/// The machine code of one model: its functions, compiled into one or more
/// modules (one per thread that compiled them). Read-only once made.
pub struct Machine {
    modules: Vec<JITModule>,
    entries: Vec<Entry>,
    params: usize,
}

/// Some of a machine's functions: a finalized module and, per function,
/// its index in the machine, its id in the module and its arity.
pub(super) struct Part {
    module: JITModule,
    functions: Vec<(usize, FuncId, usize, usize)>,
}

// SAFETY: a part is a finalized module that is only moved (from the thread
// that compiled it to the one that makes the `Machine`), never used there
// but through `Machine::new`, which reads the functions' addresses.
unsafe impl Send for Part {}

impl Part {
    /// The finalized `module` and its `functions`.
    pub(super) fn new(module: JITModule, functions: Vec<(usize, FuncId, usize, usize)>) -> Self {
        Self { module, functions }
    }
}

// SAFETY: after `Machine::new` the modules are never used through `&self`
// (only dropped, through `&mut self`), and the code it holds is immutable
// executable memory; the function pointers are plain addresses into it.
// Calling them from several threads at once is calling pure functions of
// their arguments (they read `params` and `args`, write `out`, and call the
// runtime's thread-safe routines).
unsafe impl Send for Machine {}
// SAFETY: as for `Send`: nothing is mutated through a shared reference.
unsafe impl Sync for Machine {}

impl Machine {
    /// The `count` functions of the finalized `parts`, each compiled with
    /// the arity given; every function reads at most `params` parameter
    /// values. A function no part holds is never called (its calls give NaN).
    pub(super) fn new(parts: Vec<Part>, count: usize, params: usize) -> Self {
        let mut entries: Vec<Entry> = (0..count)
            .map(|_| Entry {
                code: None,
                args: usize::MAX,
                outs: usize::MAX,
            })
            .collect();
        let mut modules = Vec::with_capacity(parts.len());
        for Part { module, functions } in parts {
            for (index, id, args, outs) in functions {
                let ptr = module.get_finalized_function(id);
                // SAFETY: `ptr` is the entry of a function defined in
                // `module` with the signature `(i64, i64, i64) -> ()` in the
                // platform's C calling convention (`jit::walk::signature`),
                // which is `Raw` on this target; the module was finalized, so
                // the code is in place and executable. It stays valid while
                // `module` lives, which is as long as this `Machine`.
                let code = unsafe { std::mem::transmute::<*const u8, Raw>(ptr) };
                if let Some(e) = entries.get_mut(index) {
                    *e = Entry {
                        code: Some(code),
                        args,
                        outs,
                    };
                }
            }
            modules.push(module);
        }
        Self {
            modules,
            entries,
            params,
        }
    }

    /// The typed handle of the function defined `index`-th, if its arity
    /// is `A → O`.
    pub(super) fn id<const A: usize, const O: usize>(&self, index: usize) -> Option<FnId<A, O>> {
        let e = self.entries.get(index)?;
        (e.args == A && e.outs == O).then_some(FnId {
            index: index as u32,
            _arity: PhantomData,
        })
    }

    /// How many parameter values the functions read at most.
    pub fn params(&self) -> usize {
        self.params
    }

    /// Call `f` with the parameter values `params` and `args`, into `out`.
    /// `out` is all NaN when `params` is shorter than [`params`](Self::params)
    /// or `f` is not this machine's (nothing is read then).
    #[inline]
    pub fn call<const A: usize, const O: usize>(
        &self,
        f: FnId<A, O>,
        params: &[f64],
        args: &[f64; A],
        out: &mut [f64; O],
    ) {
        match self.entries.get(f.index as usize) {
            Some(&Entry {
                code: Some(code),
                args: a,
                outs: o,
            }) if a == A && o == O && params.len() >= self.params => {
                // SAFETY: the function reads `params[..self.params]` (checked
                // above to exist), `args[..A]` and writes `out[..O]` (its
                // arity, checked above against the arrays' types), and
                // nothing else; the code lives as long as `self`.
                unsafe { code(params.as_ptr(), args.as_ptr(), out.as_mut_ptr()) }
            }
            _ => out.fill(f64::NAN),
        }
    }
}

impl Drop for Machine {
    fn drop(&mut self) {
        for module in self.modules.drain(..) {
            // SAFETY: the code is reachable only through `self.entries`,
            // which is dropped with `self`: no function is running (calls
            // borrow `self`) and none can be called afterwards.
            unsafe { module.free_memory() }
        }
    }
}

impl std::fmt::Debug for Machine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Machine")
            .field("functions", &self.entries.len())
            .field("params", &self.params)
            .finish()
    }
}

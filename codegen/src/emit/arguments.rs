//! Generated functions share their signatures across models (a mapping
//! always takes `(p, x0, a, x1, b)`, a normal field `(p, x, y, phi)`), but a
//! model need not use every argument: a stick mapping of a belt that stands
//! still (`V = 0`) never reads its start phase `a`, an unforced model's
//! normal field never reads `phi`. Such an argument is renamed `_name`, so
//! that the generated code compiles without warnings for every valid model,
//! whichever driver includes it.

use std::collections::HashSet;

use syn::visit::Visit;
use syn::visit_mut::VisitMut;

/// Rename every function argument its body does not use to `_name`.
pub fn mark_unused(file: &mut syn::File) {
    Marker.visit_file_mut(file);
}

struct Marker;

impl VisitMut for Marker {
    fn visit_item_fn_mut(&mut self, f: &mut syn::ItemFn) {
        mark(&mut f.sig, &f.block);
        syn::visit_mut::visit_item_fn_mut(self, f);
    }

    fn visit_impl_item_fn_mut(&mut self, f: &mut syn::ImplItemFn) {
        mark(&mut f.sig, &f.block);
        syn::visit_mut::visit_impl_item_fn_mut(self, f);
    }
}

/// Every identifier in a body (a superset of the arguments it uses).
#[derive(Default)]
struct Names(HashSet<String>);

impl<'ast> Visit<'ast> for Names {
    fn visit_ident(&mut self, i: &'ast proc_macro2::Ident) {
        self.0.insert(i.to_string());
    }
}

fn mark(sig: &mut syn::Signature, body: &syn::Block) {
    let mut names = Names::default();
    names.visit_block(body);
    for arg in &mut sig.inputs {
        let syn::FnArg::Typed(typed) = arg else {
            continue;
        };
        let syn::Pat::Ident(pat) = typed.pat.as_mut() else {
            continue;
        };
        let name = pat.ident.to_string();
        if !name.starts_with('_') && !names.0.contains(&name) {
            pat.ident = syn::Ident::new(&format!("_{name}"), pat.ident.span());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_unused_arguments_are_renamed() {
        let mut file: syn::File = syn::parse_quote! {
            pub fn f(p: &Params, x0: f64, a: Phase, b: Phase) -> f64 { p.V * (b.phi() - x0) }
            impl T for U { fn g(p: &Params, phi: f64) -> f64 { p.c } }
        };
        mark_unused(&mut file);
        let text = quote::quote!(#file).to_string();
        assert!(text.contains("_a : Phase"), "{text}");
        assert!(text.contains("p : & Params , x0 : f64"), "{text}");
        assert!(text.contains("b : Phase"), "{text}");
        assert!(text.contains("_phi : f64"), "{text}");
    }
}

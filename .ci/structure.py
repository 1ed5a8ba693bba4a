#!/usr/bin/env python3
"""Structure limits of issue 16 (docs/ARCHITECTURE.md, "Conventions"):
source files above 700 lines outside #[cfg(test)], functions above 120
lines (a closure counts in its function), and import circles between the
modules of a crate (file-level `use crate::...` edges, comments ignored).
Prints what breaks a limit and exits 1; prints nothing when all hold.
Run from the repository root: python3 .ci/structure.py
"""
import os,re,sys
big=[];fns=[];bad=[]
for root,_,files in os.walk('crates'):
    if '/tests' in root or '/benches' in root or 'target' in root: continue
    for f in files:
        if not f.endswith('.rs') or f=='tests.rs': continue
        p=os.path.join(root,f); L=open(p).read().split('\n')
        n=len(L)
        for i,l in enumerate(L):
            if l.startswith('#[cfg(test)]'): n=i;break
        if n>700: big.append((n,p))
        # functions
        i=0
        while i<n:
            l=L[i]
            m=re.match(r'\s*(pub(\([^)]*\))?\s+)?(const\s+)?(async\s+)?(unsafe\s+)?fn\s+(\w+)',l)
            if m:
                # find opening brace
                depth=0;started=False;j=i
                while j<n:
                    for ch in L[j]:
                        if ch=='{': depth+=1;started=True
                        elif ch=='}': depth-=1
                    if started and depth==0: break
                    if not started and L[j].rstrip().endswith(';'): break
                    j+=1
                if started and j-i+1>120: fns.append((j-i+1,p,m.group(6),i+1))
                i=j+1 if started else i+1
            else: i+=1
for b in sorted(big): print('FILE',*b)
for f in sorted(fns): print('FN',*f)

# --- import circles ---
# module graph per crate at file granularity; refs via crate::a::b or super::
res={}
for crate in os.listdir('crates'):
    src=f'crates/{crate}/src'
    if not os.path.isdir(src): continue
    mods={}
    for root,_,files in os.walk(src):
        for f in files:
            if not f.endswith('.rs'): continue
            p=os.path.join(root,f); rel=os.path.relpath(p,src)[:-3].split('/')
            if rel[-1] in('mod','lib','main'): rel=rel[:-1]
            if rel and rel[-1]=='tests': continue
            txt="\n".join(l for l in open(p).read().split("\n") if not l.strip().startswith("//"))
            i=txt.find('#[cfg(test)]')
            if i>=0: txt=txt[:i]
            mods['::'.join(rel)]=txt
    names=set(mods)
    g={m:set() for m in mods}
    for m,txt in mods.items():
        # expand use groups crudely: capture crate::path tokens
        for mm in re.finditer(r'crate::([\w:]+)',txt):
            parts=mm.group(1).split('::')
            # longest prefix that's a module
            for k in range(len(parts),0,-1):
                c='::'.join(parts[:k])
                if c in names:
                    if c!=m and not m.startswith(c+'::') and not c.startswith(m+'::') : g[m].add(c)
                    break
        for mm in re.finditer(r'\bcrate::\{([^}]*)\}',txt):
            for item in mm.group(1).split(','):
                parts=item.strip().split('::')
                for k in range(len(parts),0,-1):
                    c='::'.join(parts[:k])
                    if c in names:
                        if c!=m and not m.startswith(c+'::') and not c.startswith(m+'::'): g[m].add(c)
                        break
        base=m.split('::')[:-1] if m else []
        for mm in re.finditer(r'\bsuper::(\w+)',txt):
            c='::'.join(base+[mm.group(1)]) if base else mm.group(1)
            # super of file module m (non-mod.rs) -> parent module; crude
    # find cycles via SCC
    idx={};low={};st=[];on=set();out=[];n=[0]
    sys.setrecursionlimit(10000)
    def sc(v):
        idx[v]=low[v]=n[0];n[0]+=1;st.append(v);on.add(v)
        for w in g[v]:
            if w not in idx: sc(w);low[v]=min(low[v],low[w])
            elif w in on: low[v]=min(low[v],idx[w])
        if low[v]==idx[v]:
            comp=[]
            while True:
                w=st.pop();on.discard(w);comp.append(w)
                if w==v:break
            if len(comp)>1: out.append(comp)
    for v in g:
        if v not in idx: sc(v)
    for c in out: print('CIRCLE',crate,sorted(c)); bad.append(c)


sys.exit(1 if (big or fns or bad) else 0)

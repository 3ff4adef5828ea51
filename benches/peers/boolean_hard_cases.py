"""manifold3d on the hard cases of booleans, for the table beside
wingedge's (`cargo run --release -p wingedge-bench --bin hard_cases`), and the Menger
sponge of depth 3 by differences (tests/it/boolean/hard.rs):
`python3 benches/peers/boolean_hard_cases.py`."""
import manifold3d as m3d, numpy as np
M=m3d.Manifold
def cube(lo,hi): return M.cube(tuple(np.subtract(hi,lo))).translate(tuple(lo))
a=cube([0,0,0],[1,1,1])
def show(name, r):
    print(f"{name:40s} vol {r.volume():.17g} genus {r.genus()} tris {r.num_tri()} shells {len(r.decompose())} status {r.status()}")
show("face-sharing union", a + cube([1,0,0],[2,1,1]))
show("face-sharing intersection", a ^ cube([1,0,0],[2,1,1]))
show("edge-sharing union", a + cube([1,1,0],[2,2,1]))
show("vertex-sharing union", a + cube([1,1,1],[2,2,2]))
show("cube minus itself", a - a)
show("cube minus coplanar-topped box", a - cube([.25,.25,.5],[.75,.75,1]))
b=cube([-1,-1,-1],[1,1,1]); r=b.rotate((0,0,1e-12*180/np.pi))
show("rot 1e-12 union", b + r); show("rot 1e-12 intersection", b ^ r); show("rot 1e-12 difference", b - r)
up=np.nextafter(1.0,2.0)
c=cube([0,0,0],[up,up,up])
show("1ulp union", a + c); show("1ulp intersection", a ^ c); show("1ulp difference", c - a)
s=M.sphere(1.0, 40); t=s.translate((0.3,0.2,0.1))
for scale,off in [(1,0),(1,1e8),(1e-8,0)]:
    A=s.scale((scale,)*3).translate((off,)*3); B=t.scale((scale,)*3).translate((off,)*3)
    show(f"spheres diff scale {scale} offset {off}", A - B)

# The Menger sponge of depth 3 on a cube of side 27.
import time
M = m3d.Manifold
t=time.time()
tunnels=[]
for level in (1,2,3):
    n=3**level; s=27.0/n
    for a in range(1,n,3):
        for b in range(1,n,3):
            for axis in range(3):
                lo=[a*s,b*s,-1.0]; hi=[(a+1)*s,(b+1)*s,28.0]
                lo=lo[-axis:]+lo[:-axis] if axis else lo; hi=hi[-axis:]+hi[:-axis] if axis else hi
                size=[h-l for h,l in zip(hi,lo)]
                tunnels.append(M.cube(tuple(size)).translate(tuple(lo)))
u=M.batch_boolean(tunnels, m3d.OpType.Add)
r=M.cube((27,27,27))-u
print(len(tunnels), r.volume(), r.genus(), r.num_tri(), time.time()-t)

#!/usr/bin/env python3
# A noisy copy of a closed binary-PLY mesh, as docs/mesh-repair.md uses: Loop-subdivided --subdiv
# times, then each vertex moved along its normal by Gaussian noise of --sigma x d_m (of the
# subdivided mesh). Needs numpy. Usage: noisy-copy.py IN.ply OUT.ply --subdiv 1 --sigma 0.1 --seed 1
import argparse
import numpy as np

def read_ply(path):
    with open(path,'rb') as f:
        data=f.read()
    end=data.index(b'end_header\n')+len(b'end_header\n')
    header=data[:end].decode('latin1').splitlines()
    nv=nf=0; vprops=[]; fprops=[]; cur=None; comments=[]
    for l in header:
        p=l.split()
        if p[0]=='element':
            cur=p[1]
            if cur=='vertex': nv=int(p[2])
            if cur=='face': nf=int(p[2])
        elif p[0]=='property' and cur=='vertex': vprops.append(p[1:])
        elif p[0]=='property' and cur=='face': fprops.append(p[1:])
        elif p[0]=='comment': comments.append(l)
    assert all(t[0]=='float' for t in vprops) and len(vprops)==3, vprops
    v=np.frombuffer(data,dtype='<f4',count=nv*3,offset=end).reshape(nv,3).astype(np.float64)
    off=end+nv*12
    fields=[('n','u1'),('i','<i4',3)]+[('x%d'%k,'<i4') for k in range(len(fprops)-1)]
    rec=np.dtype(fields)
    fa=np.frombuffer(data,dtype=rec,count=nf,offset=off)
    assert (fa['n']==3).all()
    return v, fa['i'].astype(np.int64), comments
def write_ply(path, v, f, comments=()):
    h=['ply','format binary_little_endian 1.0',*comments,f'element vertex {len(v)}','property float x','property float y','property float z',f'element face {len(f)}','property list uchar int vertex_indices','end_header']
    rec=np.dtype([('n','u1'),('i','<i4',3)])
    fa=np.zeros(len(f),dtype=rec); fa['n']=3; fa['i']=f
    with open(path,'wb') as o:
        o.write(('\n'.join(h)+'\n').encode()); o.write(v.astype('<f4').tobytes()); o.write(fa.tobytes())
def vertex_normals(v,f):
    n=np.cross(v[f[:,1]]-v[f[:,0]], v[f[:,2]]-v[f[:,0]])
    vn=np.zeros_like(v)
    for k in range(3): np.add.at(vn,f[:,k],n)
    return vn/np.linalg.norm(vn,axis=1,keepdims=True)
def mean_edge(v,f):
    e=np.concatenate([f[:,[0,1]],f[:,[1,2]],f[:,[2,0]]]); e.sort(axis=1); e=np.unique(e,axis=0)
    return np.linalg.norm(v[e[:,0]]-v[e[:,1]],axis=1).mean(), e

def loop_subdivide(v,f):
    nv=len(v)
    e=np.concatenate([f[:,[0,1]],f[:,[1,2]],f[:,[2,0]]]); opp=np.concatenate([f[:,2],f[:,0],f[:,1]])
    es=np.sort(e,axis=1); key=es[:,0]*nv+es[:,1]
    uk,inv=np.unique(key,return_inverse=True)
    ne=len(uk); ea=uk//nv; eb=uk%nv
    oppsum=np.zeros((ne,3)); np.add.at(oppsum,inv,v[opp]); cnt=np.bincount(inv,minlength=ne)
    assert (cnt==2).all()
    ev=3/8*(v[ea]+v[eb])+1/8*oppsum
    val=np.bincount(np.concatenate([ea,eb]),minlength=nv)
    nbsum=np.zeros_like(v); np.add.at(nbsum,ea,v[eb]); np.add.at(nbsum,eb,v[ea])
    beta=np.where(val==3,3/16,3/(8*val))
    vv=(1-val*beta)[:,None]*v+beta[:,None]*nbsum
    nvv=np.concatenate([vv,ev]); mid=inv.reshape(3,-1).T+nv  # mids of edges 01,12,20 per face
    a,b,c=f[:,0],f[:,1],f[:,2]; m01,m12,m20=mid[:,0],mid[:,1],mid[:,2]
    nf=np.concatenate([np.stack([a,m01,m20],1),np.stack([m01,b,m12],1),np.stack([m20,m12,c],1),np.stack([m01,m12,m20],1)])
    return nvv,nf
p=argparse.ArgumentParser(); p.add_argument('inp'); p.add_argument('out'); p.add_argument('--subdiv',type=int,default=0)
p.add_argument('--sigma',type=float,default=0.1); p.add_argument('--seed',type=int,default=0)
a=p.parse_args()
v,f,com=read_ply(a.inp)
for _ in range(a.subdiv): v,f=loop_subdivide(v,f)
dm,_=mean_edge(v,f); n=vertex_normals(v,f)
rng=np.random.default_rng(a.seed)
v=v+n*(rng.standard_normal(len(v))*a.sigma*dm)[:,None]
write_ply(a.out,v,f,[f'comment noisy copy of {a.inp.split("/")[-1]}: Loop subdivision x{a.subdiv}, normal noise {a.sigma} d_m, seed {a.seed}'])
print(a.out,len(v),len(f),dm)

#!/usr/bin/env python3
# Compares two renderings of the same view (docs/isosurfaces.md): the share of pixels both cover
# (silhouette intersection over union, against the corner pixel's background), how many pixels of
# each silhouette lie more than 1, 2 or 3 pixels from the other, and the mean luminance of each
# over their common pixels in a 3 x 3 grid of image regions.
# Usage: docs/isosurface-metrics.py VOLUME.png MESH.png (with the sss Python module importable,
# e.g. PYTHONPATH=build/python).
import sys
import numpy as np, sss
def load(f):
    a=np.asarray(sss.load_png(f), dtype=float)
    if a.max()>1.5: a=a/255
    return a[...,:3]
v=load(sys.argv[1]); m=load(sys.argv[2])
bg=v[0,0]
mv=np.abs(v-bg).sum(-1)>0.03; mm=np.abs(m-bg).sum(-1)>0.03
inter=(mv&mm).sum(); union=(mv|mm).sum()
print("silhouette: volume %d px, mesh %d px, IoU %.3f (only volume %d, only mesh %d)"%(mv.sum(),mm.sum(),inter/union,(mv&~mm).sum(),(mm&~mv).sum()))
def grown(mask, pixels):
    # The mask grown by `pixels` in every direction, diagonals included (Chebyshev distance).
    out=mask.copy()
    for dy in range(-pixels,pixels+1):
        for dx in range(-pixels,pixels+1):
            out|=np.roll(np.roll(mask,dy,0),dx,1)
    return out
far=lambda a,b,k:(a&~grown(b,k)).sum()
print("silhouette pixels more than 1 / 2 / 3 pixels from the other silhouette: volume %d / %d / %d, mesh %d / %d / %d"
      %(far(mv,mm,1),far(mv,mm,2),far(mv,mm,3),far(mm,mv,1),far(mm,mv,2),far(mm,mv,3)))
lum=lambda a:(0.2126*a[...,0]+0.7152*a[...,1]+0.0722*a[...,2])
lv,lm=lum(v),lum(m)
H,W=mv.shape
both=mv&mm
for i,name in enumerate(['top','middle','bottom']):
    for j,cn in enumerate(['left','centre','right']):
        sl=(slice(i*H//3,(i+1)*H//3),slice(j*W//3,(j+1)*W//3))
        b=both[sl]
        if b.sum()<50: continue
        print("| %s %s | %d | %.3f | %.3f | %.2f |"%(name,cn,b.sum(),lv[sl][b].mean(),lm[sl][b].mean(),lm[sl][b].mean()/lv[sl][b].mean()))

// Push-out slice with crack planes: meshes/slice.geo with the circumference
// cut at the crack directions too, so that each crack plane (a ray from the
// tube axis, from r = R to the slice's outer boundary, through the whole
// thickness) is a mesh surface. pushout duplicates its nodes afterwards
// (cpp/mesh/cracks.cpp), as it does for the steel-concrete interface.
//
// The sectors are computed by pushout (cpp/mesh/cracks.cpp: slice_sectors)
// and passed as constants: nb boundaries, boundary i at angle a_i [rad] from
// the tube centre (increasing), its outer point (ox_i, oy_i) on the slice
// boundary, and n_i elements along the circumference from boundary i to
// boundary i + 1 (cyclic), and the radial divisions: nr1, nr2 and the
// growth q (cpp/mesh/size.cpp). Without cracks
// pushout meshes slice.geo instead. Units: mm.
DefineConstant[
  shape = {0, Name "outer_shape: 0 square, 1 circle"},
  W = {100, Name "width (square side or circle diameter)"},
  L = {20, Name "thickness"},
  D = {20, Name "tube outer diameter"},
  Di = {16, Name "tube inner diameter"},
  cx = {50, Name "tube centre x"},
  cy = {50, Name "tube centre y"},
  Ds = {30, Name "support inner diameter"},
  nq = {16, Name "elements per quarter circumference"},
  nz = {8, Name "elements through thickness"},
  ns = {3, Name "steel layers"},
  nb = {5, Name "sector boundaries"},
  // The radial divisions, computed by pushout (cpp/mesh/size.cpp,
  // slice_divisions): elements from R to the support circle, and from there
  // to the boundary along each sector boundary with growth q.
  nr1 = {5, Name "elements of the concrete ring (R..Rs)"},
  nr2 = {9, Name "elements of the graded block (Rs..boundary)"},
  q = {1.333521432163324, Name "growth of the graded block's elements"}
];

R = D / 2; Ri = Di / 2; Rs = Ds / 2;

pc = newp; Point(pc) = {cx, cy, 0};
radii[] = {Ri, R, Rs};
For k In {0:nb - 1}
  For j In {0:2}
    p[nb * j + k] = newp;
    Point(p[nb * j + k]) = {cx + radii[j] * Cos(a~{k}), cy + radii[j] * Sin(a~{k}), 0};
  EndFor
  po[k] = newp;
  Point(po[k]) = {ox~{k}, oy~{k}, 0};
EndFor

// Arcs on r = Ri, R, Rs and the outer boundary, sector k from boundary k to k+1.
For k In {0:nb - 1}
  k1 = (k + 1) % nb;
  For j In {0:2}
    arc[nb * j + k] = newc;
    Circle(arc[nb * j + k]) = {p[nb * j + k], pc, p[nb * j + k1]};
    Transfinite Curve{arc[nb * j + k]} = n~{k} + 1;
  EndFor
  outer[k] = newc;
  If (shape == 0)
    Line(outer[k]) = {po[k], po[k1]};
  Else
    Circle(outer[k]) = {po[k], pc, po[k1]};
  EndIf
  Transfinite Curve{outer[k]} = n~{k} + 1;
EndFor

// Radial lines at each boundary: tube wall, concrete ring, graded block.
For k In {0:nb - 1}
  rad0[k] = newc; Line(rad0[k]) = {p[k], p[nb + k]};
  Transfinite Curve{rad0[k]} = ns + 1;
  rad1[k] = newc; Line(rad1[k]) = {p[nb + k], p[2 * nb + k]};
  Transfinite Curve{rad1[k]} = nr1 + 1;
  rad2[k] = newc; Line(rad2[k]) = {p[2 * nb + k], po[k]};
  Transfinite Curve{rad2[k]} = nr2 + 1 Using Progression q;
EndFor

steel_surfaces[] = {};
concrete_surfaces[] = {};
For k In {0:nb - 1}
  k1 = (k + 1) % nb;
  For j In {0:2}
    c_in = arc[nb * j + k];
    If (j < 2)
      c_out = arc[nb * (j + 1) + k];
    Else
      c_out = outer[k];
    EndIf
    If (j == 0) r0 = rad0[k]; r1 = rad0[k1]; EndIf
    If (j == 1) r0 = rad1[k]; r1 = rad1[k1]; EndIf
    If (j == 2) r0 = rad2[k]; r1 = rad2[k1]; EndIf
    cl = newll; Curve Loop(cl) = {c_in, r1, -c_out, -r0};
    s = news; Plane Surface(s) = {cl};
    Transfinite Surface{s};
    Recombine Surface{s};
    If (j == 0)
      steel_surfaces[] += s;
    Else
      concrete_surfaces[] += s;
    EndIf
  EndFor
EndFor

all_surfaces[] = {steel_surfaces[], concrete_surfaces[]};
ex[] = Extrude {0, 0, L} { Surface{all_surfaces[]}; Layers{nz}; Recombine; };
steel_volumes[] = {};
concrete_volumes[] = {};
For i In {0:#all_surfaces[] - 1}
  If (i < #steel_surfaces[])
    steel_volumes[] += ex[6 * i + 1];
  Else
    concrete_volumes[] += ex[6 * i + 1];
  EndIf
EndFor

Physical Volume("steel", 1) = {steel_volumes[]};
Physical Volume("concrete", 2) = {concrete_volumes[]};

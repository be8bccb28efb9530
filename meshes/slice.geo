// Push-out slice: a steel tube in a concrete slice (paper §2.1, §4.1).
//
// Structured hexahedra: the cross-section is cut into 4 quarters (block
// corners at 45, 135, 225, 315 degrees); each quarter has three transfinite
// blocks -- the tube wall (Ri..R), a concrete ring up to the support circle
// (R..Rs) of elements of about the interface size, so that the support edge
// is a mesh line, and a graded block out to the slice boundary (square side
// or circle) -- then everything is extruded through the thickness. Steel
// and concrete share the nodes on r = R here; pushout duplicates them to
// insert the interface (joint) elements.
//
// Open it in gmsh to see the block structure; pushout sets the constants
// from the scene (gmsh -setnumber). Units: mm.
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
  // The radial divisions, computed by pushout (cpp/mesh/size.cpp,
  // slice_divisions; here the default scene's): elements from R to the
  // support circle, and from there to the boundary along each corner line
  // with growth (progression) q.
  nr1 = {5, Name "elements of the concrete ring (R..Rs)"},
  nr2 = {9, Name "elements of the graded block (Rs..boundary)"},
  q = {1.333521432163324, Name "growth of the graded block's elements"},
  // The outer ends of the block corner lines, also from pushout
  // (cpp/scene/CrackPlanes.h, block_corners): the square's corners, or the
  // circle's points at 45 + 90 k degrees.
  ox_0 = {100, Name "block corner 0 x"}, oy_0 = {100, Name "block corner 0 y"},
  ox_1 = {0, Name "block corner 1 x"}, oy_1 = {100, Name "block corner 1 y"},
  ox_2 = {0, Name "block corner 2 x"}, oy_2 = {0, Name "block corner 2 y"},
  ox_3 = {100, Name "block corner 3 x"}, oy_3 = {0, Name "block corner 3 y"}
];

R = D / 2; Ri = Di / 2; Rs = Ds / 2;

pc = newp; Point(pc) = {cx, cy, 0};
radii[] = {Ri, R, Rs};
For k In {0:3}
  a = Pi / 4 + k * Pi / 2;
  For j In {0:2}
    p[4 * j + k] = newp;
    Point(p[4 * j + k]) = {cx + radii[j] * Cos(a), cy + radii[j] * Sin(a), 0};
  EndFor
  po[k] = newp;
  Point(po[k]) = {ox~{k}, oy~{k}, 0};
EndFor

// Arcs on r = Ri, R, Rs and the outer boundary, quarter k from corner k to k+1.
For k In {0:3}
  k1 = (k + 1) % 4;
  For j In {0:2}
    arc[4 * j + k] = newc;
    Circle(arc[4 * j + k]) = {p[4 * j + k], pc, p[4 * j + k1]};
    Transfinite Curve{arc[4 * j + k]} = nq + 1;
  EndFor
  outer[k] = newc;
  If (shape == 0)
    Line(outer[k]) = {po[k], po[k1]};
  Else
    Circle(outer[k]) = {po[k], pc, po[k1]};
  EndIf
  Transfinite Curve{outer[k]} = nq + 1;
EndFor

// Radial lines at each corner: tube wall, concrete ring, graded block.
For k In {0:3}
  rad0[k] = newc; Line(rad0[k]) = {p[k], p[4 + k]};
  Transfinite Curve{rad0[k]} = ns + 1;
  rad1[k] = newc; Line(rad1[k]) = {p[4 + k], p[8 + k]};
  Transfinite Curve{rad1[k]} = nr1 + 1;
  rad2[k] = newc; Line(rad2[k]) = {p[8 + k], po[k]};
  Transfinite Curve{rad2[k]} = nr2 + 1 Using Progression q;
EndFor

steel_surfaces[] = {};
concrete_surfaces[] = {};
For k In {0:3}
  k1 = (k + 1) % 4;
  For j In {0:2}
    c_in = arc[4 * j + k];
    If (j < 2)
      c_out = arc[4 * (j + 1) + k];
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

// One extrusion for all blocks, so that neighbouring blocks share faces.
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

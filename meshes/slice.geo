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
  ox_3 = {100, Name "block corner 3 x"}, oy_3 = {0, Name "block corner 3 y"},
  // mesh.graded_lines = "radial" (a square slice): the graded block's lines
  // run along rays from the tube axis, line j from the support circle at
  // 45 + 90 j / nq degrees to (bx_j, by_j) on the boundary (pushout passes
  // the 4 nq of them, each square corner at the end of its nearest ray:
  // cpp/scene/CrackPlanes.h, radial_line_ends); the block corners are then
  // (bx_j, by_j) for j = k nq, and ox_k, oy_k are not used.
  radial = {0, Name "graded lines along rays (1) or to the square's corners (0)"}
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
  If (radial == 0)
    po[k] = newp;
    Point(po[k]) = {ox~{k}, oy~{k}, 0};
  EndIf
EndFor
If (radial == 1)
  For j In {0:4 * nq - 1}
    pb[j] = newp;
    Point(pb[j]) = {bx~{j}, by~{j}, 0};
  EndFor
  For k In {0:3}
    po[k] = pb[k * nq];
  EndFor
EndIf

// Arcs on r = Ri, R, Rs and the outer boundary, quarter k from corner k to k+1.
For k In {0:3}
  k1 = (k + 1) % 4;
  For j In {0:2}
    arc[4 * j + k] = newc;
    Circle(arc[4 * j + k]) = {p[4 * j + k], pc, p[4 * j + k1]};
    Transfinite Curve{arc[4 * j + k]} = nq + 1;
  EndFor
  If (radial == 1)
    // The quarter's boundary as nq segments between the lines' ends (a
    // square corner is one of them), one element each.
    For i In {0:nq - 1}
      seg[k * nq + i] = newc;
      Line(seg[k * nq + i]) = {pb[k * nq + i], pb[(k * nq + i + 1) % (4 * nq)]};
      Transfinite Curve{seg[k * nq + i]} = 2;
    EndFor
  Else
    outer[k] = newc;
    If (shape == 0)
      Line(outer[k]) = {po[k], po[k1]};
    Else
      Circle(outer[k]) = {po[k], pc, po[k1]};
    EndIf
    Transfinite Curve{outer[k]} = nq + 1;
  EndIf
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
concrete_sides[] = {}; // each concrete surface's boundary curves
For k In {0:3}
  k1 = (k + 1) % 4;
  For j In {0:2}
    c_in = arc[4 * j + k];
    If (j == 0) r0 = rad0[k]; r1 = rad0[k1]; EndIf
    If (j == 1) r0 = rad1[k]; r1 = rad1[k1]; EndIf
    If (j == 2) r0 = rad2[k]; r1 = rad2[k1]; EndIf
    If (j < 2)
      loop[] = {c_in, r1, -arc[4 * (j + 1) + k], -r0};
    ElseIf (radial == 0)
      loop[] = {c_in, r1, -outer[k], -r0};
    Else
      loop[] = {c_in, r1};
      For i In {nq - 1:0:-1}
        loop[] += -seg[k * nq + i];
      EndFor
      loop[] += -r0;
    EndIf
    cl = newll; Curve Loop(cl) = loop[];
    s = news; Plane Surface(s) = {cl};
    If (j == 2 && radial == 1)
      // Its four corners, as its outer side is nq curves.
      Transfinite Surface{s} = {p[8 + k], p[8 + k1], po[k1], po[k]};
    Else
      Transfinite Surface{s};
    EndIf
    Recombine Surface{s};
    If (j == 0)
      steel_surfaces[] += s;
    Else
      concrete_surfaces[] += s;
      concrete_sides[] += #loop[];
    EndIf
  EndFor
EndFor

// One extrusion for all blocks, so that neighbouring blocks share faces.
// It lists for each surface its top, its volume and a side per boundary
// curve: 6 entries for a block of 4 sides, 5 + nq for a graded block with
// radial lines.
all_surfaces[] = {steel_surfaces[], concrete_surfaces[]};
ex[] = Extrude {0, 0, L} { Surface{all_surfaces[]}; Layers{nz}; Recombine; };
steel_volumes[] = {};
concrete_volumes[] = {};
at = 0; // the surface's first entry in ex[]
For i In {0:#all_surfaces[] - 1}
  If (i < #steel_surfaces[])
    steel_volumes[] += ex[at + 1];
    at += 6;
  Else
    concrete_volumes[] += ex[at + 1];
    at += 2 + concrete_sides[i - #steel_surfaces[]];
  EndIf
EndFor

Physical Volume("steel", 1) = {steel_volumes[]};
Physical Volume("concrete", 2) = {concrete_volumes[]};

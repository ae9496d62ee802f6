"""CalculiX input decks, runs and result readers: the one home of threepart's CalculiX model.

threepart uses CalculiX (``ccx``, Debian's ``calculix-ccx``) as an outside
referee: an independent finite-element code, with its own elements (CPE8,
plane strain) and its own penalty contact, that is judged against the closed
form. This package builds its meshes (:mod:`.mesh`), writes its decks
(:mod:`.deck`, CalculiX's dialect of the Abaqus input format), runs ``ccx``
(:mod:`.run`) and reads its results back (:mod:`.read`, the one reader of
CalculiX's output). It imports no solver; the core (``threepart/*.py``) never
imports it.

Meshes (threepart.calculix.mesh)
--------------------------------
Model              -- a whole two-body plane mesh of a punch on a block, ready for ``write_deck``
build_model        -- the whole-model two-body gmsh mesh (second order) of a three-part punch
build_finite_model -- the validity map's finite punch (exact arcs, flanks, height H) on its block, or its half
Mesh               -- the small-slope benchmark's half model (``benchmarks/small_slope_calculix.py``)
build_half_mesh    -- its gmsh mesh
GMSH_TO_CCX        -- gmsh element type -> (CalculiX element, number of corner nodes)

Decks (threepart.calculix.deck)
-------------------------------
DeckSettings    -- mesh size, penalty stiffness, punch stiffening, pair or stiff punch, block size
check_mesh_size -- ``h`` if the contact width holds W_OVER_H elements, else ValueError
W_OVER_H        -- the admissible elements across the contact width W = a + c
write_deck      -- the deck of a model: sets, materials, contact, load at ``s``, free or suppressed tilt
Material        -- the half model's block and its stiffened punch
half_deck       -- the deck of the half model (a force or a descent)
CONVENTIONS     -- the comment block every deck carries (units, conventions, pitfalls)
nodes_text, elements_text, nset_text, surface_text, material_text, contact_text,
equation_text, boundary_text, step_text -- the deck's cards
Keyword         -- one keyword card of a deck
parse_deck      -- a minimal keyword parser (``*KEYWORD, PARAM=...`` and data lines) for checks

Running (threepart.calculix.run)
--------------------------------
ccx_available   -- whether ``ccx`` is on the PATH
run_ccx         -- run ``ccx`` on a deck in a directory (one thread); raises CcxMissing, CcxError
CcxError        -- ``ccx`` ran but failed, or wrote no result
CcxMissing      -- ``ccx`` is not on the PATH

Reading (threepart.calculix.read)
---------------------------------
read_frd         -- the nodal result blocks of an ``.frd`` file (DISP, STRESS, CONTACT), last increment
read_frd_nodes   -- the node coordinates of an ``.frd`` file
read_dat         -- the printed blocks of a ``.dat`` file (node sets, contact output), last time
read_reaction    -- the total reaction force of a printed node set (``.dat``)
read_descent     -- the punch's descent (``.dat``)
read_increments  -- how many increments the step took (``.sta``)
deck_nodes       -- the node coordinates of a deck's ``*NODE`` cards
nodal_forces     -- the contact's force at each slave node, ``-2 CELS / COPEN`` (plane models)
nodal_areas      -- the nodes' shares ``∫N_i dx`` of a quadratic surface (L/6, 2L/3, L/6)
vertex_flags     -- vertex or midside, from the counts of expanded nodes
element_vertices -- vertex or midside, from the elements
dealternate      -- nodal values freed of the vertex/midside alternation (a local fit)
DEALTERNATE_NODES -- the nodes on each side of that fit
force_pressure   -- the contact pressure from the nodal forces: over the shares, de-alternated
penalty_stiffness -- the penalty ``K = CPRESS / -COPEN`` at the closed nodes
contact_pressure -- the pressure points ``(x, p, info)`` of one ``.frd`` or ``.dat``
surface_gap      -- the block's surface nodes (deformed) and their gap to the punch
surface_pressure -- the contact pressure along the block's surface from a run (x, p, gap, CPRESS)
SurfacePressure  -- what surface_pressure returns
contact_edge     -- a contact end from the gap just outside it (``gap^(2/3)`` linear)
centre_pressure  -- ``p(0)`` of a symmetric pressure from a fit about the centre
"""
from __future__ import annotations

from .deck import (CONVENTIONS, W_OVER_H, DeckSettings, Keyword, Material, boundary_text, check_mesh_size,
                   contact_text, elements_text, equation_text, half_deck, material_text, nodes_text,
                   nset_text, parse_deck, step_text, surface_text, write_deck)
from .mesh import GMSH_TO_CCX, Mesh, Model, build_finite_model, build_half_mesh, build_model
from .read import (DEALTERNATE_NODES, SurfacePressure, centre_pressure, contact_edge, contact_pressure,
                   dealternate, deck_nodes, element_vertices, force_pressure, nodal_areas, nodal_forces,
                   penalty_stiffness, read_dat, read_descent, read_frd, read_frd_nodes, read_increments,
                   read_reaction, surface_gap, surface_pressure, vertex_flags)
from .run import CcxError, CcxMissing, ccx_available, run_ccx

__all__ = ["DeckSettings", "Model", "build_model", "build_finite_model", "write_deck", "CONVENTIONS",
           "parse_deck", "Keyword", "ccx_available", "run_ccx", "CcxMissing", "CcxError", "read_frd",
           "read_frd_nodes", "read_reaction", "read_dat", "nodal_forces", "nodal_areas", "dealternate",
           "force_pressure", "DEALTERNATE_NODES", "read_descent", "surface_pressure", "SurfacePressure",
           "contact_edge", "centre_pressure", "Material", "Mesh", "build_half_mesh", "half_deck",
           "nodes_text", "elements_text", "nset_text", "surface_text", "material_text",
           "contact_text", "equation_text", "boundary_text", "step_text", "GMSH_TO_CCX", "W_OVER_H",
           "check_mesh_size", "read_increments", "deck_nodes", "vertex_flags", "element_vertices",
           "penalty_stiffness", "contact_pressure", "surface_gap"]

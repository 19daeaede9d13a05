-- The Newtonian square at t = 0+ against the finite-element fields of
-- ../shared/reference-fields (REFERENCES.md section 1), point by point, through
-- scripts/compare_fields.lua: the velocity in the interior (more than 3 dx from the plates
-- and the free side) and the pressure there.
-- Measured (one thread, t = 0.005, the FE grid mapped onto the gap h = 0.995, the SPH
-- fields fitted by sph.flows.mls): rms u / v 0.0077 / 0.0103 at dx = 1/20, 0.0070 / 0.0068
-- at 1/40 (the FE field is at h = 1; the mapping leaves about 0.005); rms p 0.270 / 0.252, mostly a uniform offset of +0.24 (7 %
-- of the centre pressure 3.21) set by the free side's pressure (2.38 against FE's 1.92 at
-- x = 0.45, y = 0.5, dx = 1/40). Bounds: the 1/20 figures with a margin of about a half.
local T = require "sph.test"
local top = arg[0]:match("^(.*)/tests/lua/[^/]+$") or "."
local ref = top .. "/../shared/reference-fields"
local f = io.open(ref .. "/square_newtonian_grid.csv")
if not f then
  print("# " .. ref .. " not found: the pointwise FE comparison is skipped")
  T.done()
end
f:close()

T.case("Newtonian square against the FE fields, dx = 1/20", function()
  local text, status = T.script("compare_fields.lua", ("Bn=0 n=20 t=0.005 threads=1 ref=%s"):format(ref))
  T.check(status == 0, "compare_fields.lua runs", text)
  local u, v, p = text:match("interior%s+%d+%s+([%d.]+)%s+([%d.]+)%s+([%d.]+)")
  u, v, p = tonumber(u), tonumber(v), tonumber(p)
  T.check(u ~= nil, "the interior row is printed", text)
  if not u then return end
  print(("# interior rms errors: u %.4f, v %.4f, p %.4f"):format(u, v, p))
  T.below(u, 0.012, "interior rms error of u against FE")
  T.below(v, 0.015, "interior rms error of v against FE")
  T.below(p, 0.4, "interior rms error of p against FE (centre pressure 3.21)")
end)

T.done()

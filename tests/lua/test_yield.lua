-- A Bingham square under three quarters of its plane-strain yield load only creeps
-- (../shared/REFERENCES.md section 3: F_y = Bn F_tau,y(1) = 2.015 Bn; with M = 800 the plate
-- moves at 1e-3 or less, so h(1) > 0.98). The short version of make validate's section 3:
-- Bn = 10, Re = 1, dx = 1/20, to t = 1.
local T = require "sph.test"
local squeeze = require "sph.squeeze"
local refs = require "sph.references"

T.case("Bingham square under 0.75 F_y creeps only", function()
  -- measured (one thread): h(1) = 0.9949, V(1) = 0.0001, 1,611 steps (0.9977 / 0.9989 at
  -- dx = 1/40, 1/80 in make validate; 0.959 / 0.978 with the viscosity from the particles'
  -- rate). Bound: REFERENCES.md's h(1) > 0.98.
  local Bn = 10
  local F = 0.75 * Bn * refs.FTY[1]
  local w, top = squeeze.build{ dx = 1 / 20, Re = 1, Bn = Bn, M = 800, mode = "load", F = -F, h_min = 0.25,
                                world = { threads = 1 } }
  w:run{ until_t = 1 }
  print(string.format("# 0.75 F_y (F = %.4f): h(1) = %.4f, V(1) = %.5f, %d steps", F, top.position, top:velocity(), w.steps))
  T.check(top.position > 0.98, "under 0.75 F_y the square keeps h(1) > 0.98", string.format("h(1) = %.4f", top.position))
end)

T.done()

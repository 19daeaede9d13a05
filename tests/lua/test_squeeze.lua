-- Squeeze-flow regressions (paper's scaling, half sample with a symmetry plane).
-- Bingham (explicit viscosity) Bn = 0.5, M = 100, Re = 10, constant velocity: reaches
--    h = 0.6 with no NaN and a max density error under 1 %.
local squeeze = require "sph.squeeze"
local T = require "sph.test"
local o = ... or {}

T.case("Bingham squeeze reaches h = 0.6", function()
  local w, top = squeeze.build{ dx = 1 / 40, Re = 10, Bn = 0.5, M = 100, mode = "velocity", world = { threads = o.threads } }
  local emax = 0
  w:run{ until_t = 0.41, every = 0.01, each = function(ww) emax = math.max(emax, ww:stats().max_density_error) end }
  print(string.format("# Bingham: h = %.3f after %d steps, max density error %.4f", top.position, w.steps, emax))
  T.below(top.position, 0.6 + 1e-9, "Bingham squeeze reaches h = 0.6")
  -- measured 0.0063 (density_relax 0.3, shifting 20)
  T.below(emax, 0.01, "Bingham squeeze max density error under 1 %")
end)

T.done()

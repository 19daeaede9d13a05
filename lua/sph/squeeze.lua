-- The squeeze-flow test in the paper's scaling (H = U = mu = 1, rho = Re, tau0 = Bn,
-- m = M): a rectangle of height 1 and width 2a = 1 between two plates, the lower one fixed,
-- the upper one at constant velocity or under a constant load. Only the half x >= 0 is
-- simulated, with a symmetry plane at x = 0; forces and masses are the whole sample's.
local sph = require "sph"

local S = {}

-- Lubrication theory for the whole sample (PHYSICS.md), area A = 1 per unit depth.
function S.newtonian_force(h, V, mu) return (mu or 1) * (V or 1) / h ^ 6 end
function S.newtonian_height(t, F, mu) return (1 + 5 * F * t / (mu or 1)) ^ (-1 / 5) end
function S.plastic_force(h, tau0) return tau0 / (2 * h ^ 3) end
function S.stop_height(tau0, F) return (tau0 / (2 * F)) ^ (1 / 3) end

-- opts: dx, Re, Bn, M, mode ("velocity" | "load"), V (plate speed, default 1), F (load,
-- a compressive force is negative, as in the paper), h_min (how thin the sample will get:
-- sizes the plates), width and height (the half sample's, default 0.5 and 1: a film
-- started thin is e.g. width = 1.6, height = 0.2), and any sph.world option (viscosity,
-- threads, ...) via opts.world. Any other key is an error: a misspelt option would
-- otherwise be ignored.
local KEYS = { dx = true, Re = true, Bn = true, M = true, mode = true, V = true, F = true, h_min = true,
               width = true, height = true, world = true }
function S.build(opts)
  for k in pairs(opts) do
    if not KEYS[k] then
      local names = {}
      for n in pairs(KEYS) do names[#names + 1] = n end
      table.sort(names)
      error(string.format("squeeze.build: unknown option '%s' (the options are %s; engine options go in world = {...})",
        tostring(k), table.concat(names, ", ")), 2)
    end
  end
  if opts.mode ~= nil and opts.mode ~= "velocity" and opts.mode ~= "load" then
    error(string.format("squeeze.build: mode must be \"velocity\" or \"load\", got %s", tostring(opts.mode)), 2)
  end
  local dx = opts.dx or 1 / 40
  local Re, Bn, M = opts.Re or 1, opts.Bn or 0, opts.M or 800
  local h_min = opts.h_min or 0.3
  -- shifting 20: without it the stretched lattice opens voids inside the sample, taken for
  -- free surface, and the run fails near h = 0.6 (measured, Newtonian, dx = 1/40)
  local wopts = { dx = dx, rho = Re, symmetry = { x = 0 }, shifting = 20 }
  for k, v in pairs(opts.world or {}) do wopts[k] = v end
  local w = sph.world(wopts)
  local mat = Bn > 0 and sph.bingham{ mu = 1, tau0 = Bn, m = M } or sph.newtonian{ mu = 1 }
  local a0, h0 = opts.width or 0.5, opts.height or 1
  w:fill{ rect = { 0, 0, a0, h0 }, material = mat }
  -- plates: 3h thick (the kernel support), wide enough for the spread sample (a = a0 h0 / h)
  local T = math.ceil(3 * w.h / dx - 1e-9) * dx
  local half = math.max(1.5, 1.25 * a0 * h0 / h_min) + 4 * dx
  half = math.ceil(half / dx) * dx
  local bottom = w:plate{ rect = { -half, -T, half, 0 } }
  local top = w:plate{ rect = { -half, h0, half, h0 + T }, axis = "y" }
  if (opts.mode or "velocity") == "velocity" then
    top:velocity(-(opts.V or 1))
  else
    top:load(opts.F or -10)
  end
  return w, top, bottom, mat
end

return S

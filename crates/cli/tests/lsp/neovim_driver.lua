-- Drives headless Neovim for test_neovim.py, after an editors/neovim recipe was loaded as the init file
-- (`nvim --headless -u RECIPE -c "luafile neovim_driver.lua"`): opens the plan's files, waits for the
-- server's diagnostics, presses the recipe's keys and writes what it saw, as JSON, to the plan's `out`.
-- It never fails by itself: whatever did not happen within the time limit is missing from the JSON (and
-- named in `errors`), and test_neovim.py says what is wrong.
local plan = vim.json.decode(os.getenv("URDF_NVIM_PLAN"))
local timeout = plan.timeout_ms
local result = { errors = {}, buffers = {} }
local get_clients = vim.lsp.get_clients or vim.lsp.get_active_clients

local function wait(what, predicate)
  if vim.wait(timeout, predicate, 20) then
    return true
  end
  table.insert(result.errors, "timed out waiting for " .. what)
  return false
end

local function ours(buf)
  local found = {}
  for _, client in ipairs(get_clients()) do
    if client.name == "urdf_validate" and vim.lsp.buf_is_attached(buf, client.id) then
      table.insert(found, client)
    end
  end
  return found
end

local function diagnostics(buf)
  local shown = {}
  for _, d in ipairs(vim.diagnostic.get(buf)) do
    table.insert(shown, {
      lnum = d.lnum, col = d.col, end_lnum = d.end_lnum, end_col = d.end_col,
      severity = d.severity, message = d.message,
      code = d.code or (d.user_data and d.user_data.lsp and d.user_data.lsp.code),
    })
  end
  return shown
end

local function has_codes(buf, codes)
  local seen = {}
  for _, d in ipairs(diagnostics(buf)) do
    if d.code then
      seen[d.code] = true
    end
  end
  for _, code in ipairs(codes) do
    if not seen[code] then
      return false
    end
  end
  return true
end

local function floats()
  local found = {}
  for _, win in ipairs(vim.api.nvim_list_wins()) do
    if vim.api.nvim_win_get_config(win).relative ~= "" then
      table.insert(found, win)
    end
  end
  return found
end

local function close_floats()
  for _, win in ipairs(floats()) do
    vim.api.nvim_win_close(win, true)
  end
end

-- `keys` as :normal types them: <leader> is the map leader (a backslash unless set).
local function press(keys)
  vim.cmd("normal " .. keys:gsub("<leader>", vim.g.mapleader or "\\"))
end

-- The cursor on `at` = { file index (1-based), line (0-based), column (0-based) }.
local function go(bufs, at)
  vim.api.nvim_set_current_buf(bufs[at[1]])
  vim.api.nvim_win_set_cursor(0, { at[2] + 1, at[3] })
end

local function run()
  local v = vim.version()
  result.version = string.format("%d.%d.%d", v.major, v.minor, v.patch)
  local bufs = {}
  for i, file in ipairs(plan.files) do
    vim.cmd("edit " .. vim.fn.fnameescape(file))
    bufs[i] = vim.api.nvim_get_current_buf()
  end
  for i, buf in ipairs(bufs) do
    wait("a urdf_validate client attached to " .. plan.files[i], function() return #ours(buf) > 0 end)
    wait("diagnostics " .. table.concat(plan.expect[i], ", ") .. " in " .. plan.files[i], function()
      return has_codes(buf, plan.expect[i])
    end)
  end
  -- Other files, in order: which get a client. Those that should are waited for; one that should not
  -- comes first, so it had its chance by then (Neovim 0.11 attaches after the FileType event).
  result.others = {}
  local others = {}
  for i, other in ipairs(plan.others) do
    vim.cmd("edit " .. vim.fn.fnameescape(other.file))
    others[i] = vim.api.nvim_get_current_buf()
  end
  for i, other in ipairs(plan.others) do
    if other.attach then
      wait("a urdf_validate client attached to " .. other.file, function() return #ours(others[i]) > 0 end)
    end
  end
  for i, other in ipairs(plan.others) do
    result.others[other.file] = { filetype = vim.bo[others[i]].filetype, clients = #ours(others[i]) }
  end
  local clients = {}
  for _, client in ipairs(get_clients()) do
    if client.name == "urdf_validate" then
      clients[tostring(client.id)] = { root_dir = client.config.root_dir }
    end
  end
  result.clients = clients
  for i, buf in ipairs(bufs) do
    local attached = {}
    for _, client in ipairs(ours(buf)) do
      table.insert(attached, client.id)
    end
    vim.api.nvim_set_current_buf(buf)
    local maps = {}
    for name, lhs in pairs(plan.keys) do
      local map = vim.fn.maparg(lhs, "n", false, true)
      maps[name] = map.lhs and { lhs = map.lhs, buffer = map.buffer == 1 } or vim.NIL
    end
    result.buffers[i] = {
      file = vim.api.nvim_buf_get_name(buf),
      filetype = vim.bo[buf].filetype,
      omnifunc = vim.bo[buf].omnifunc,
      clients = attached,
      diagnostics = diagnostics(buf),
      maps = maps,
    }
  end

  -- Hover: the key opens a floating window holding the server's text.
  close_floats()
  go(bufs, plan.hover_at)
  press(plan.keys.hover)
  if wait("the hover window after " .. plan.keys.hover, function() return #floats() > 0 end) then
    result.hover = vim.api.nvim_buf_get_lines(vim.api.nvim_win_get_buf(floats()[1]), 0, -1, false)
  end
  close_floats()

  -- Go to definition: the key moves the cursor.
  go(bufs, plan.definition_at)
  press(plan.keys.definition)
  wait("the cursor to move after " .. plan.keys.definition, function()
    return vim.api.nvim_win_get_cursor(0)[1] ~= plan.definition_at[2] + 1
  end)
  result.definition = {
    file = vim.api.nvim_buf_get_name(0),
    line = vim.api.nvim_win_get_cursor(0)[1] - 1,
  }

  -- Code actions: the key offers them through vim.ui.select (answered with no choice).
  local offered
  vim.ui.select = function(items, opts, on_choice)
    offered = {}
    for _, item in ipairs(items) do
      table.insert(offered, opts.format_item and opts.format_item(item) or tostring(item))
    end
    on_choice(nil)
  end
  go(bufs, plan.code_action_at)
  press(plan.keys.code_action)
  wait("the code actions after " .. plan.keys.code_action, function() return offered ~= nil end)
  result.code_actions = offered

  -- Diagnostics navigation: from the first line, the key goes to the first finding.
  close_floats()
  go(bufs, { 1, 0, 0 })
  press(plan.keys.next_diagnostic)
  result.next_diagnostic_line = vim.api.nvim_win_get_cursor(0)[1] - 1
  close_floats()
end

local ok, error = pcall(run)
if not ok then
  table.insert(result.errors, tostring(error))
end
local file = assert(io.open(plan.out, "w"))
file:write(vim.json.encode(result))
file:close()
vim.cmd("qa!")

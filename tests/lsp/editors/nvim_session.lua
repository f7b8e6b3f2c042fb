-- One headless Neovim session through editors/nvim (the set-up users load): opens each model of
-- the plan in turn, waits for bodyls's diagnostics, makes the plan's edit, waits, undoes it,
-- waits, and writes what Neovim holds after each step as JSON. The comparison with bodycheck is
-- editor_diagnostics.py's.
--
--   BODYLS_PLAN=plan.json BODYLS_RESULT=out.json nvim --headless -u NONE -i NONE -n -c "luafile nvim_session.lua"
--
-- The plan: {server, editors_dir, root_dir, timeout_ms, edit_line, models: [{path, opened, edited}],
-- definition, keys, viewer}, `opened` and `edited` the number of bodycheck's findings by file, before and
-- after the edit; `definition` {path, line, column, counts}: where to go to definition at the end
-- (1-based line and byte column), with vim.lsp.buf.definition() and then with <C-]>; `keys`
-- {path, counts, typed, hover_line, hover_column}: the editor's own keys on a model, <C-x><C-o>
-- at the end of the line `typed` appended to it and K at the hover place (1-based line and byte
-- column); `stages` {path, steps: [{text, counts}]}: a model typed stage by stage into one
-- buffer (each step's text replaces the last), its diagnostics and the code actions offered on
-- each; `viewer` a model to open in bodyview with :BodyView at the end.
local plan = vim.fn.json_decode(table.concat(vim.fn.readfile(os.getenv("BODYLS_PLAN")), "\n"))
local result = { models = {}, notes = {} }

local function termcodes(keys)
  return vim.api.nvim_replace_termcodes(keys, true, false, true)
end

local function write_result()
  vim.fn.writefile({ vim.fn.json_encode(result) }, os.getenv("BODYLS_RESULT"))
end

-- Every publishDiagnostics by URI: how many so far, the last one's version and what the server
-- sent (the positions before Neovim converts them, for the independent check). Kept across
-- models: a diagnostic the server leaves behind on a closed model's files stays in the editor.
local published = {}
local versioned = false -- whether the server has named a document version
local default_handler = vim.lsp.handlers["textDocument/publishDiagnostics"]
vim.lsp.handlers["textDocument/publishDiagnostics"] = function(err, params, ctx, config)
  default_handler(err, params, ctx, config)
  local seen = published[params.uri] or { count = 0 }
  seen.count = seen.count + 1
  seen.version = params.version
  seen.raw = params.diagnostics
  published[params.uri] = seen
  versioned = versioned or params.version ~= nil
end

local server_exited = false
local function server_gone()
  return server_exited
end

local function count(uri)
  return published[uri] and published[uri].count or 0
end

-- Waits for the document's diagnostics after `before` publishes of them (for `version` when the
-- server names versions: the buffer's, as Neovim sent it), then for every file to hold as many diagnostics as bodycheck finds
-- there (`counts`: by file name): a publish for an included file may come after the document's,
-- and one clearing the previous model's files may come late. What the diagnostics are is
-- editor_diagnostics.py's to judge; a step that does not settle is left to it too.
local function wait_for(buf, uri, before, counts, step)
  local expected = {}
  for file, n in pairs(counts) do
    expected[vim.uri_from_fname(file)] = n
  end
  local function settled()
    local seen = published[uri]
    if not (seen and seen.count > before and (not versioned or seen.version == vim.lsp.util.buf_versions[buf])) then
      return false
    end
    for u, s in pairs(published) do
      if #(s.raw or {}) ~= (expected[u] or 0) then
        return false
      end
    end
    for u, n in pairs(expected) do
      if n > 0 and not published[u] then
        return false
      end
    end
    return true
  end
  vim.wait(plan.timeout_ms, function()
    return settled() or server_gone()
  end, 2)
  if server_gone() then
    error(step .. ": the server is not running (it exited or never started)")
  end
  if not settled() then
    result.unsettled = (result.unsettled or 0) + 1
    table.insert(result.notes, string.format("%s: diagnostics for %s did not settle within %d ms", step, uri, plan.timeout_ms))
    if result.unsettled >= 3 then
      error("three steps did not settle: stopping")
    end
  end
end

-- What Neovim shows: every diagnostic of every buffer (an included file's are on its own buffer),
-- its position in bytes as Neovim converted it, and the server's own numbers beside it.
local function snapshot()
  local out = {}
  for _, b in ipairs(vim.api.nvim_list_bufs()) do
    for _, d in ipairs(vim.diagnostic.get(b)) do
      local lsp = d.user_data and d.user_data.lsp or {}
      table.insert(out, {
        file = vim.api.nvim_buf_get_name(b),
        line = d.lnum + 1,
        column = d.col + 1,
        severity = d.severity,
        code = d.code or lsp.code,
      })
    end
  end
  local raw = {}
  for uri, seen in pairs(published) do
    for _, d in ipairs(seen.raw or {}) do
      table.insert(raw, {
        file = vim.uri_to_fname(uri),
        line = d.range.start.line,
        character = d.range.start.character,
        severity = d.severity,
        code = d.code,
      })
    end
  end
  return { diagnostics = out, raw = raw }
end

local function run_model(model)
  local entry = { path = model.path }
  table.insert(result.models, entry)
  local started = vim.loop.hrtime()
  vim.cmd("edit " .. vim.fn.fnameescape(model.path))
  local buf = vim.api.nvim_get_current_buf()
  if vim.bo[buf].filetype ~= "body" then
    error(model.path .. ": filetype " .. vim.bo[buf].filetype .. ", not body")
  end
  local uri = vim.uri_from_bufnr(buf)
  wait_for(buf, uri, count(uri), model.opened, model.path .. ": open")
  entry.opened = snapshot()
  entry.open_ms = (vim.loop.hrtime() - started) / 1e6

  local lines = vim.api.nvim_buf_line_count(buf)
  local before = count(uri)
  started = vim.loop.hrtime()
  vim.api.nvim_buf_set_lines(buf, lines, lines, false, { plan.edit_line })
  wait_for(buf, uri, before, model.edited, model.path .. ": edit")
  entry.edited = snapshot()
  entry.edit_ms = (vim.loop.hrtime() - started) / 1e6

  before = count(uri)
  vim.cmd("silent undo")
  if vim.api.nvim_buf_line_count(buf) ~= lines then
    error(model.path .. ": undo left " .. vim.api.nvim_buf_line_count(buf) .. " lines, not " .. lines)
  end
  wait_for(buf, uri, before, model.opened, model.path .. ": undo")
  entry.undone = snapshot()
  vim.cmd("bwipeout!")
end

-- A model typed stage by stage (the Choreonoid tutorial's SimpleTank): each step's text replaces
-- the buffer's, and once its diagnostics settle, the code actions offered on each diagnostic
-- (the titles, as a user picks them from vim.lsp.buf.code_action()).
local function run_stages(stages)
  vim.cmd("silent! %bwipeout!")
  local entries = {}
  result.stages = entries
  local uri = vim.uri_from_fname(stages.path)
  local before = count(uri)
  vim.cmd("edit " .. vim.fn.fnameescape(stages.path))
  local buf = vim.api.nvim_get_current_buf()
  for i, step in ipairs(stages.steps) do
    local entry = { actions = {} }
    table.insert(entries, entry)
    before = count(uri)
    vim.api.nvim_buf_set_lines(buf, 0, -1, false, vim.split(step.text, "\n", { plain = true }))
    wait_for(buf, uri, before, step.counts, stages.path .. ": stage " .. i)
    entry.shown = snapshot()
    -- As vim.lsp.buf.code_action() asks, with each diagnostic as the server sent it.
    for _, d in ipairs(published[uri] and published[uri].raw or {}) do
      local params = { textDocument = { uri = uri }, range = d.range, context = { diagnostics = { d } } }
      local titles = {}
      local replies, request_error = vim.lsp.buf_request_sync(buf, "textDocument/codeAction", params, plan.timeout_ms)
      entry.error = entry.error or request_error
      for _, reply in pairs(replies or {}) do
        entry.error = entry.error or (reply.err and vim.inspect(reply.err))
        for _, action in ipairs(reply.result or {}) do
          if not action.disabled then
            table.insert(titles, action.title)
          end
        end
      end
      table.insert(entry.actions, { line = d.range.start.line + 1, code = d.code, titles = titles })
    end
  end
  vim.cmd("bwipeout!")
end

-- The first bytes of the answer to GET / at `url` (an http://127.0.0.1:PORT/ address).
local function http_get(url)
  local host, port = url:match("^http://([%d%.]+):(%d+)/")
  if not host then
    return "not a loopback URL"
  end
  local chunks, finished = {}, false
  local tcp = vim.loop.new_tcp()
  tcp:connect(host, tonumber(port), function(err)
    if err then
      table.insert(chunks, "connect: " .. err)
      finished = true
      return
    end
    tcp:write("GET / HTTP/1.0\r\nHost: " .. host .. ":" .. port .. "\r\n\r\n")
    tcp:read_start(function(read_err, chunk)
      if read_err or not chunk then
        tcp:close()
        finished = true
      else
        table.insert(chunks, chunk)
      end
    end)
  end)
  vim.wait(plan.timeout_ms, function()
    return finished
  end, 5)
  return table.concat(chunks):sub(1, 400)
end

-- :BodyView on a model: the server's answer, what it asked the editor to show, and the page.
local function check_viewer(path)
  local entry = {}
  result.viewer = entry
  vim.lsp.handlers["window/showDocument"] = function(_, params)
    entry.shown = params.uri
    return { success = true }
  end
  local show_message = vim.lsp.handlers["window/showMessage"]
  vim.lsp.handlers["window/showMessage"] = function(err, params, ctx, config)
    entry.message = params.message
    return show_message(err, params, ctx, config)
  end
  vim.cmd("edit " .. vim.fn.fnameescape(path))
  local done = false
  require("bodyls").open_viewer(0, function(url, err)
    entry.url = url
    entry.error = err and err.message
    done = true
  end)
  vim.wait(plan.timeout_ms, function()
    return done and (entry.error or entry.shown or entry.message)
  end, 5)
  if entry.url then
    entry.page = http_get(entry.url)
  end
end

-- Go to definition (vim.lsp.buf.definition, what `gd` maps to in most set-ups) on a name the
-- model's SubBody file defines: where the editor lands (file, 1-based line, 1-based byte column).
local function check_definition(def)
  local entry = {}
  result.definition = entry
  local uri = vim.uri_from_fname(def.path)
  local before = count(uri) -- the model was opened before: wait for this opening's check
  vim.cmd("edit " .. vim.fn.fnameescape(def.path))
  local buf = vim.api.nvim_get_current_buf()
  wait_for(buf, uri, before, def.counts, def.path .. ": open for definition")
  vim.api.nvim_win_set_cursor(0, { def.line, def.column - 1 })
  vim.lsp.buf.definition()
  vim.wait(plan.timeout_ms, function()
    return vim.api.nvim_get_current_buf() ~= buf
  end, 5)
  local cursor = vim.api.nvim_win_get_cursor(0)
  entry.file = vim.api.nvim_buf_get_name(0)
  entry.line = cursor[1]
  entry.column = cursor[2] + 1

  -- The same with the editor's own key: <C-]> jumps to the tag the set-up's tagfunc finds.
  local tag = {}
  result.tag_definition = tag
  vim.cmd("buffer " .. buf)
  vim.api.nvim_win_set_cursor(0, { def.line, def.column - 1 })
  local ok, failure = pcall(vim.api.nvim_feedkeys, termcodes("<C-]>"), "x", false)
  tag.error = not ok and tostring(failure) or nil
  cursor = vim.api.nvim_win_get_cursor(0)
  tag.file = vim.api.nvim_buf_get_name(0)
  tag.line = cursor[1]
  tag.column = cursor[2] + 1
end

-- The editor's own keys on a model: <C-x><C-o> (omnifunc) at the end of a line typed below the
-- model's last one, and K (hover) on a key. What each shows, for editor_diagnostics.py to judge.
local function check_keys(plan_keys)
  local entry = {}
  result.keys = entry
  -- The models opened before are closed: their files' diagnostics are cleared, as a wait expects.
  vim.cmd("silent! %bwipeout!")
  local uri = vim.uri_from_fname(plan_keys.path)
  local before = count(uri)
  vim.cmd("edit " .. vim.fn.fnameescape(plan_keys.path))
  local buf = vim.api.nvim_get_current_buf()
  wait_for(buf, uri, before, plan_keys.counts, plan_keys.path .. ": open for the keys")

  -- Completion: Insert mode stays on until a timer sees the completion (or gives up) and
  -- leaves it (the one match is inserted as it is; <C-y> without a menu would copy the
  -- character above); feedkeys with "x!" returns when Insert mode ends.
  local last = vim.api.nvim_buf_line_count(buf)
  vim.api.nvim_buf_set_lines(buf, last, last, false, { plan_keys.typed })
  vim.api.nvim_win_set_cursor(0, { last + 1, 0 })
  local started = vim.loop.now()
  local timer = vim.loop.new_timer()
  timer:start(10, 10, vim.schedule_wrap(function()
    local shown = #vim.fn.complete_info({ "items" }).items > 0
    if shown or vim.loop.now() - started > plan.timeout_ms then
      entry.completion_shown = shown
      timer:stop()
      timer:close()
      vim.api.nvim_feedkeys(termcodes("<Esc>"), "n", false)
    end
  end))
  local ok, failure = pcall(vim.api.nvim_feedkeys, termcodes("A<C-x><C-o>"), "x!", false)
  entry.completion_error = not ok and tostring(failure) or nil
  entry.completed = vim.api.nvim_buf_get_lines(buf, last, last + 1, false)[1]
  vim.cmd("silent undo")

  -- Hover: K opens a floating window with the server's text.
  local function floats()
    local found = {}
    for _, win in ipairs(vim.api.nvim_list_wins()) do
      if vim.api.nvim_win_get_config(win).relative ~= "" then
        table.insert(found, win)
      end
    end
    return found
  end
  vim.api.nvim_win_set_cursor(0, { plan_keys.hover_line, plan_keys.hover_column - 1 })
  ok, failure = pcall(vim.api.nvim_feedkeys, "K", "x", false)
  entry.hover_error = not ok and tostring(failure) or nil
  vim.wait(plan.timeout_ms, function()
    return #floats() > 0
  end, 5)
  local shown = {}
  for _, win in ipairs(floats()) do
    vim.list_extend(shown, vim.api.nvim_buf_get_lines(vim.api.nvim_win_get_buf(win), 0, -1, false))
    vim.api.nvim_win_close(win, true)
  end
  entry.hover = table.concat(shown, "\n")
  vim.cmd("bwipeout!")
end

local ok, failure = pcall(function()
  vim.o.swapfile = false
  vim.o.hidden = true
  vim.opt.runtimepath:append(plan.editors_dir .. "/nvim")
  -- Edits are sent at once: the server's own debounce is what a check waits for.
  require("bodyls").setup({
    cmd = { plan.server },
    root_dir = plan.root_dir,
    flags = { debounce_text_changes = 0 },
    on_exit = function()
      server_exited = true
    end,
  })
  for _, model in ipairs(plan.models) do
    run_model(model)
  end
  if plan.definition then
    check_definition(plan.definition)
  end
  if plan.keys then
    check_keys(plan.keys)
  end
  if plan.stages then
    run_stages(plan.stages)
  end
  if plan.viewer then
    check_viewer(plan.viewer)
  end
end)
if not ok then
  result.error = tostring(failure)
end
write_result()
vim.cmd("qall!")

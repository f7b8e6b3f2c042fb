;;; eglot_session.el --- one batch Emacs session of eglot driving bodyls  -*- lexical-binding: t -*-

;; BODYLS_PLAN=plan.json BODYLS_RESULT=out.json emacs --batch -l eglot_session.el
;;
;; Loads editors/emacs/bodyls.el (the set-up users load), opens each model of the plan in turn
;; (body-mode, eglot), waits for bodyls's diagnostics, makes the plan's edit, waits, undoes it,
;; waits, and writes what flymake holds after each step as JSON; then the hover eldoc shows on
;; the plan's `keys' model, and the plan's `stages' typed one after another into one buffer.  The comparison with bodycheck
;; is editor_diagnostics.py's.  Batch Emacs runs no idle timers, so what they do in an editor is
;; done here in their place: sending the edit (eglot's `eglot-send-changes-idle-time') and
;; starting flymake's backends once a buffer is managed (its display-deferred start).

;;; Code:

(require 'json)
(require 'cl-lib)

(defvar bodyls-test-plan
  (with-temp-buffer
    (insert-file-contents (getenv "BODYLS_PLAN"))
    (json-parse-buffer :object-type 'alist :array-type 'list)))

(defun bodyls-test--get (key) (alist-get key bodyls-test-plan))

(load (expand-file-name "emacs/bodyls.el" (bodyls-test--get 'editors_dir)) nil t)
(setq bodyls-program (bodyls-test--get 'server))
(setq make-backup-files nil create-lockfiles nil auto-save-default nil)
(setq eglot-sync-connect t eglot-autoshutdown nil)
;; No events buffer: eglot pretty-prints every message into it (a second per large model here).
(setq eglot-events-buffer-size 0)
;; Whole messages per read: 130 diagnostics are about 60 kB of JSON (4 kB reads by default).
(setq read-process-output-max (* 1024 1024))

;; One server for every model: the whole plan is one project.
(let ((root (file-name-as-directory (expand-file-name (bodyls-test--get 'root_dir)))))
  (add-hook 'project-find-functions
            (lambda (dir)
              (when (string-prefix-p root (file-name-as-directory (expand-file-name dir)))
                (cons 'transient root)))))

;; Every publishDiagnostics by URI: how many so far, the last one's version and what the server
;; sent (the positions before eglot converts them, for the independent check).  Kept across
;; models: a diagnostic the server leaves behind on a closed model's files stays in the editor.
(defvar bodyls-test--published (make-hash-table :test #'equal))
(defvar bodyls-test--versioned nil "Whether the server has named a document version.")
(defvar bodyls-test--notes nil)

(defvar bodyls-test--message nil "The server's last window/showMessage.")

(advice-add 'eglot-handle-notification :after
            (lambda (_server method &rest params)
              (when (eq method 'window/showMessage)
                (setq bodyls-test--message (plist-get params :message)))
              (when (eq method 'textDocument/publishDiagnostics)
                (let ((seen (gethash (plist-get params :uri) bodyls-test--published)))
                  (when (plist-get params :version) (setq bodyls-test--versioned t))
                  (puthash (plist-get params :uri)
                           (list :count (1+ (or (plist-get seen :count) 0))
                                 :version (plist-get params :version)
                                 :raw (plist-get params :diagnostics))
                           bodyls-test--published)))))

(defun bodyls-test--count (uri)
  (or (plist-get (gethash uri bodyls-test--published) :count) 0))

(defun bodyls-test--settled (uri before expected)
  "The document's diagnostics came after BEFORE publishes of them (for the buffer's version when
the server names versions), and every file holds as many as EXPECTED (URI to count) says."
  (let ((seen (gethash uri bodyls-test--published))
        (ok t))
    (and seen (> (plist-get seen :count) before)
         (or (not bodyls-test--versioned) (equal (plist-get seen :version) eglot--versioned-identifier))
         (progn
           (maphash (lambda (u s)
                      (unless (= (length (plist-get s :raw)) (or (gethash u expected) 0)) (setq ok nil)))
                    bodyls-test--published)
           (maphash (lambda (u n) (when (and (> n 0) (not (gethash u bodyls-test--published))) (setq ok nil)))
                    expected)
           ok))))

(defun bodyls-test--wait (uri before counts step)
  "Waits until the step settles (`bodyls-test--settled'); a publish for an included file may
come after the document's, and one clearing the previous model's files may come late.  What the
diagnostics are is editor_diagnostics.py's to judge; a step that does not settle is left to it."
  (let ((deadline (+ (float-time) (/ (bodyls-test--get 'timeout_ms) 1000.0)))
        (expected (make-hash-table :test #'equal)))
    (dolist (entry counts)
      (puthash (eglot--path-to-uri (symbol-name (car entry))) (cdr entry) expected))
    (while (and (not (bodyls-test--settled uri before expected)) (< (float-time) deadline))
      (accept-process-output nil 0.002))
    (unless (bodyls-test--settled uri before expected)
      (push (format "%s: diagnostics for %s did not settle within %s ms" step uri (bodyls-test--get 'timeout_ms))
            bodyls-test--notes)
      (when (>= (length bodyls-test--notes) 3) (error "three steps did not settle: stopping")))))

(defun bodyls-test--severity (type)
  (pcase type ('eglot-error 1) ('eglot-warning 2) (_ 3)))

(defun bodyls-test--code (text)
  ;; eglot shows a diagnostic as "SOURCE [CODE]: MESSAGE".
  (when (string-match "\\[\\([^]]+\\)\\]:" text) (match-string 1 text)))

(defun bodyls-test--snapshot ()
  "What flymake shows: the visited buffer's diagnostics (line and byte column of their start as
eglot placed them) and the list-only ones of files not visited (line and UTF-16 column, as eglot
keeps them), and the server's own numbers."
  (let (shown raw (line 1) (from (point-min)))
    ;; In buffer order, counting lines from the previous one: line-number-at-pos counts from the
    ;; start each time.
    (dolist (d (sort (flymake-diagnostics) (lambda (a b) (< (flymake-diagnostic-beg a) (flymake-diagnostic-beg b)))))
      (save-excursion
        (goto-char (flymake-diagnostic-beg d))
        (setq line (+ line (count-lines from (line-beginning-position)))
              from (line-beginning-position))
        (push `((file . ,(buffer-file-name))
                (line . ,line)
                (column . ,(1+ (length (encode-coding-string
                                        (buffer-substring-no-properties (line-beginning-position) (point))
                                        'utf-8))))
                (severity . ,(bodyls-test--severity (flymake-diagnostic-type d)))
                (code . ,(bodyls-test--code (flymake-diagnostic-text d))))
              shown)))
    ;; As flymake's project diagnostics list them: a visited file's own buffer has its
    ;; diagnostics, whatever list-only ones eglot kept from before it was visited.
    (dolist (entry flymake-list-only-diagnostics)
      (dolist (d (unless (find-buffer-visiting (car entry)) (cdr entry)))
        (let ((at (flymake-diagnostic-beg d)))
          (push `((file . ,(car entry))
                  (line . ,(car at))
                  (utf16_column . ,(cdr at))
                  (severity . ,(bodyls-test--severity (flymake-diagnostic-type d)))
                  (code . ,(bodyls-test--code (flymake-diagnostic-text d))))
                shown))))
    (maphash (lambda (uri seen)
               (seq-doseq (d (plist-get seen :raw))
                 (let ((start (plist-get (plist-get d :range) :start)))
                   (push `((file . ,(eglot--uri-to-path uri))
                           (line . ,(plist-get start :line))
                           (character . ,(plist-get start :character))
                           (severity . ,(plist-get d :severity))
                           (code . ,(plist-get d :code)))
                         raw))))
             bodyls-test--published)
    `((diagnostics . ,(vconcat shown)) (raw . ,(vconcat raw)))))

(defun bodyls-test--model (model)
  (let* ((path (alist-get 'path model))
         (entry (list (cons 'path path)))
         (started (float-time))
         (opened-before (bodyls-test--count (eglot--path-to-uri path))))
    (find-file path)
    (setq buffer-read-only nil)  ; the corpus is read-only on disk; the edit is never saved
    (unless (eq major-mode 'body-mode) (error "%s: %s, not body-mode" path major-mode))
    (run-hooks 'post-command-hook)  ; eglot-ensure connects after the command that opened the file
    (unless eglot--managed-mode (error "%s: eglot does not manage the buffer" path))
    (flymake-start)
    (let ((uri (eglot--path-to-uri path)))
      (bodyls-test--wait uri opened-before (alist-get 'opened model) (concat path ": open"))
      (push (cons 'opened (bodyls-test--snapshot)) entry)
      (push (cons 'open_ms (* 1000 (- (float-time) started))) entry)
      (let ((before (bodyls-test--count uri))
            (text (buffer-string)))
        (undo-boundary)
        (save-excursion
          (goto-char (point-max))
          (unless (bolp) (insert "\n"))
          (insert (bodyls-test--get 'edit_line) "\n"))
        (undo-boundary)
        (setq started (float-time))
        (eglot--signal-textDocument/didChange)
        (bodyls-test--wait uri before (alist-get 'edited model) (concat path ": edit"))
        (push (cons 'edited (bodyls-test--snapshot)) entry)
        (push (cons 'edit_ms (* 1000 (- (float-time) started))) entry)
        (setq before (bodyls-test--count uri))
        (let ((last-command nil)) (undo))
        (unless (equal (buffer-string) text) (error "%s: undo did not restore the text" path))
        (eglot--signal-textDocument/didChange)
        (bodyls-test--wait uri before (alist-get 'opened model) (concat path ": undo"))
        (push (cons 'undone (bodyls-test--snapshot)) entry)))
    (set-buffer-modified-p nil)
    (kill-buffer)
    (nreverse entry)))

(defun bodyls-test--viewer (path)
  "C-c C-v (`bodyls-open-viewer') on PATH: the URL bodyls answers with and the first bytes of
the page there."
  (find-file path)
  (run-hooks 'post-command-hook)
  (let* ((url (bodyls-open-viewer))
         (url-proxy-services nil)
         (page (and url (with-current-buffer (url-retrieve-synchronously url t t (/ (bodyls-test--get 'timeout_ms) 1000))
                          (buffer-substring-no-properties (point-min) (min (point-max) 400))))))
    (accept-process-output nil 0.1)  ; the message the server sends beside its answer
    `((url . ,url) (message . ,bodyls-test--message) (page . ,page))))

(defun bodyls-test--hover (keys)
  "The hover eldoc shows (eglot's own rendering) at the plan's place in the KEYS model."
  (let* ((path (alist-get 'path keys))
         (uri (eglot--path-to-uri path))
         (before (bodyls-test--count uri))
         (shown nil))
    (find-file path)
    (run-hooks 'post-command-hook)
    (flymake-start)
    (bodyls-test--wait uri before (alist-get 'counts keys) (concat path ": open for hover"))
    (goto-char (point-min))
    (forward-line (1- (alist-get 'hover_line keys)))
    (forward-char (1- (alist-get 'hover_column keys)))
    (eglot-hover-eldoc-function (lambda (info &rest _) (setq shown (or info ""))))
    (let ((deadline (+ (float-time) (/ (bodyls-test--get 'timeout_ms) 1000.0))))
      (while (and (not shown) (< (float-time) deadline))
        (accept-process-output nil 0.005)))
    (set-buffer-modified-p nil)
    (kill-buffer)
    `((hover . ,(and shown (substring-no-properties shown))))))

(defun bodyls-test--stages (stages)
  "The model of STAGES typed stage by stage: each step's text replaces the buffer's; once its
diagnostics settle, what flymake shows and the code actions offered on each diagnostic the
server published (their titles, as `eglot-code-actions' offers them)."
  (let* ((path (alist-get 'path stages))
         (uri (eglot--path-to-uri path))
         (entries nil))
    (find-file path)
    (run-hooks 'post-command-hook)
    (flymake-start)
    (dolist (step (alist-get 'steps stages))
      (let ((before (bodyls-test--count uri))
            (actions nil))
        (erase-buffer)
        (insert (alist-get 'text step))
        (eglot--signal-textDocument/didChange)
        (bodyls-test--wait uri before (alist-get 'counts step) (format "%s: stage %d" path (1+ (length entries))))
        (seq-doseq (d (plist-get (gethash uri bodyls-test--published) :raw))
          (let* ((reply (jsonrpc-request (eglot--current-server-or-lose) :textDocument/codeAction
                                         (list :textDocument (list :uri uri) :range (plist-get d :range)
                                               :context (list :diagnostics (vector d)))))
                 (titles (cl-loop for a across reply unless (plist-get a :disabled) collect (plist-get a :title))))
            (push `((line . ,(1+ (plist-get (plist-get (plist-get d :range) :start) :line)))
                    (code . ,(plist-get d :code))
                    (titles . ,(vconcat titles)))
                  actions)))
        (push `((shown . ,(bodyls-test--snapshot)) (actions . ,(vconcat (nreverse actions)))) entries)))
    (set-buffer-modified-p nil)
    (kill-buffer)
    (vconcat (nreverse entries))))

(defvar bodyls-test--viewer nil)
(defvar bodyls-test--keys nil)
(defvar bodyls-test--stages nil)

(let ((result nil))
  (condition-case failure
      (progn
        (dolist (model (bodyls-test--get 'models))
          (push (bodyls-test--model model) result))
        (when (bodyls-test--get 'keys)
          (setq bodyls-test--keys (bodyls-test--hover (bodyls-test--get 'keys))))
        (when (bodyls-test--get 'stages)
          (setq bodyls-test--stages (bodyls-test--stages (bodyls-test--get 'stages))))
        (when (bodyls-test--get 'viewer)
          (setq bodyls-test--viewer (bodyls-test--viewer (bodyls-test--get 'viewer)))))
    (error (setq result (cons `((error . ,(error-message-string failure))) result))))
  (let ((error-entry (cl-find-if (lambda (e) (alist-get 'error e)) result)))
    (with-temp-file (getenv "BODYLS_RESULT")
      (insert (json-encode
               `((models . ,(vconcat (nreverse (cl-remove-if (lambda (e) (alist-get 'error e)) result))))
                 (notes . ,(vconcat (reverse bodyls-test--notes)))
                 (viewer . ,bodyls-test--viewer)
                 (keys . ,bodyls-test--keys)
                 (stages . ,bodyls-test--stages)
                 (error . ,(and error-entry (alist-get 'error error-entry)))))))))

(kill-emacs 0)
;;; eglot_session.el ends here
